#pragma once
// `gyrotherm plan`'s options (sim/util/option_table.h) and the request
// they make (studies/plan/plan.h; run_plan checks the values before it
// searches).

#include <string>
#include <vector>

#include "sim/util/option_table.h"
#include "studies/plan/plan.h"

namespace gyrotherm::studies {

struct PlanCommandOptions {
  plan::PlanRequest request;  // every option but --range and --json; the lists split at commas
  std::vector<double> range;  // --range LO,HI
  bool json = false;  // print the JSON rather than the text (the caller's choice)
};

const OptionTable<PlanCommandOptions>& plan_option_table();

// The request: --range two numbers; no --scenario: `default_scenario` (the
// command line's is scenarios/cycle.toml).
plan::PlanRequest plan_request(const PlanCommandOptions& options, const std::string& default_scenario);

}  // namespace gyrotherm::studies
