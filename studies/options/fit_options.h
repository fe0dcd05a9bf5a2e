#pragma once
// `gyrotherm fit`'s options (sim/util/option_table.h) and the request
// they make (studies/fit/fit_run.h).

#include <string>
#include <vector>

#include "studies/fit/fit_run.h"
#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {

struct FitCommandOptions {
  std::string data;
  ModelOptions model;
  long budget = 0;
  double target = 0.0;
  std::vector<std::string> engine_options;  // --option KEY=VALUE
  std::string output;
  bool json = false;  // print the fit's JSON rather than the text (the caller's choice)
  DataOptions data_options;
};

const OptionTable<FitCommandOptions>& fit_option_table();

// The request, checked in the command line's order: the model's terms, the
// engine's name, its settings and options, then the data options.
FitRequest fit_request(const FitCommandOptions& options);

}  // namespace gyrotherm::studies
