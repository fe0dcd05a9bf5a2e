#pragma once
// `gyrotherm simulate`'s options (sim/util/option_table.h) and the
// request they make (sim/simulation_run.h).

#include "sim/simulation_run.h"
#include "sim/util/option_table.h"

namespace gyrotherm::studies {

struct SimulateCommandOptions {
  sim::SimulateRequest request;  // every option but --json
  bool json = false;  // print the JSON rather than the text (the caller's choice)
};

const OptionTable<SimulateCommandOptions>& simulate_option_table();

// The request (simulate_to_files checks the files and --hidden).
sim::SimulateRequest simulate_request(const SimulateCommandOptions& options);

}  // namespace gyrotherm::studies
