#pragma once
// `gyrotherm diagnose`'s options (sim/util/option_table.h) and the
// request they make (studies/diagnose/diagnose_run.h).

#include <string>

#include "studies/diagnose/diagnose_run.h"
#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {

struct DiagnoseCommandOptions {
  std::string data;
  ModelOptions model;
  std::string candidates;  // a comma list, or +NAME/-NAME
  std::string plots;
  bool json = false;  // print the JSON rather than the text (the caller's choice)
  DataOptions data_options;
};

const OptionTable<DiagnoseCommandOptions>& diagnose_option_table();

// The request (without progress), checked in the command line's order: the
// model's terms, the engine, then the data options.
DiagnoseRequest diagnose_request(const DiagnoseCommandOptions& options);

}  // namespace gyrotherm::studies
