#pragma once
// `gyrotherm compensate`'s options (sim/util/option_table.h) and the
// request they make (studies/fit/compensate_run.h).

#include "studies/fit/compensate_run.h"
#include "sim/util/option_table.h"

namespace gyrotherm::studies {

struct CompensateCommandOptions {
  CompensateRequest request;  // data, --fit, -o, --causal and the column options (unset: the fit's)
  bool json = false;  // print the JSON rather than the text (the caller's choice)
};

const OptionTable<CompensateCommandOptions>& compensate_option_table();

// The request (run_compensate checks the columns against the fit's).
CompensateRequest compensate_request(const CompensateCommandOptions& options);

}  // namespace gyrotherm::studies
