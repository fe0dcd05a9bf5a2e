#include "studies/options/simulate_options.h"

#include "sim/effects/effect.h"

namespace gyrotherm::studies {

const OptionTable<SimulateCommandOptions>& simulate_option_table() {
  using O = SimulateCommandOptions;
  using R = sim::SimulateRequest;
  static const OptionTable<O> table{
      "simulate",
      {nested_row("scenario", "Scenario file (scenarios/*.toml)", &O::request, &R::scenario, true),
       nested_row("--rig", "Rig file (overrides the scenario's)", &O::request, &R::rig),
       nested_row("--gyro", "Gyro file (overrides the scenario's)", &O::request, &R::gyro),
       nested_row("--seed", "Noise seed (overrides the scenario's)", &O::request, &R::seed),
       nested_row("--hidden", "Hidden effect TERM=COEF, repeatable; TERM one of " + effects::hidden_names(), &O::request,
                  &R::hidden),
       nested_row("-o,--output", "The record: a CSV, or a PX4 ULog (.ulg) or an ArduPilot DataFlash log (.bin) (a .truth.json goes beside it)", &O::request, &R::output, true),
       nested_row("--plot", "Also draw temperatures and 100 s averages of the output into this PNG", &O::request,
                  &R::plot),
       field_row<O>("--json", "Print one JSON object instead of text", &O::json)}};
  return table;
}

sim::SimulateRequest simulate_request(const SimulateCommandOptions& options) { return options.request; }

}  // namespace gyrotherm::studies
