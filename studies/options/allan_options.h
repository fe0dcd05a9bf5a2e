#pragma once
// `gyrotherm allan`'s options (sim/util/option_table.h) and the request
// they make (studies/allan/allan_study.h).

#include <string>

#include "studies/allan/allan_study.h"
#include "studies/options/pipeline_options.h"

namespace gyrotherm::studies {

struct AllanCommandOptions {
  AllanRequest request;  // data, --fit, --tau-max, --ci, --plot
  std::string taus = "octave";
  bool json = false;  // print the JSON rather than the text (the caller's choice)
  // Without --avg. Its columns and units start unset (ColumnMap::unset()):
  // those given are laid over the fit's with a fit, over the defaults without.
  DataOptions data_options = [] {
    DataOptions d;
    d.pipeline.columns = fit::ColumnMap::unset();
    return d;
  }();
};

const OptionTable<AllanCommandOptions>& allan_option_table();

// The request: --taus one of octave, decade, all; --tau-max ≥ 0; --ci in
// (0, 1); the data options when there is no fit (with one, the fit's, but
// for the columns and units given).
AllanRequest allan_request(const AllanCommandOptions& options);

}  // namespace gyrotherm::studies
