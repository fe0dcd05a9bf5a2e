#pragma once
// `gyrotherm check`'s options (sim/util/option_table.h) and the
// request they make (studies/check/check_run.h).

#include "studies/check/check_run.h"
#include "sim/util/option_table.h"

namespace gyrotherm::studies {

struct CheckCommandOptions {
  CheckRequest request;
  bool json = false;  // print the JSON rather than the text
};

const OptionTable<CheckCommandOptions>& check_option_table();

CheckRequest check_request(const CheckCommandOptions& options);

}  // namespace gyrotherm::studies
