#include "studies/options/simulate_options.h"

#include "sim/effects/effect.h"

namespace gyrotherm::studies {

const OptionTable<SimulateCommandOptions>& simulate_option_table() {
  using O = SimulateCommandOptions;
  static const OptionTable<O> table = [] {
    OptionTable<O> t{"simulate", {}};
    const auto row = [&](const char* names, std::string help, auto field, bool required = false) {
      t.rows.push_back(nested_row(names, std::move(help), &O::request, field, required));
    };
    using R = sim::SimulateRequest;
    row("scenario", "Scenario file (scenarios/*.toml)", &R::scenario, true);
    row("--rig", "Rig file (overrides the scenario's)", &R::rig);
    row("--gyro", "Gyro file (overrides the scenario's)", &R::gyro);
    row("--seed", "Noise seed (overrides the scenario's)", &R::seed);
    row("--hidden", "Hidden effect TERM=COEF, repeatable; TERM one of " + effects::hidden_names(), &R::hidden);
    row("-o,--output", "Output CSV (a .truth.json goes beside it)", &R::output, true);
    row("--plot", "Also draw temperatures and 100 s averages of the output into this PNG", &R::plot);
    t.rows.push_back(field_row<O>("--json", "Print one JSON object instead of text", &O::json));
    return t;
  }();
  return table;
}

sim::SimulateRequest simulate_request(const SimulateCommandOptions& options) { return options.request; }

}  // namespace gyrotherm::studies
