// gyrotherm simulate SCENARIO.toml [--rig R.toml] [--gyro G.toml] [--seed N]
//                    [--hidden TERM=COEF ...] -o OUT.csv [--plot PNG] [--json]
// (studies/options/simulate_options.h, sim/simulation_run.h)

#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/simulate_options.h"

namespace gyrotherm::app {

void add_simulate_command(CLI::App& app, Run* run) {
  add_table_command<studies::SimulateCommandOptions>(app, run, "simulate", "Simulate a thermal test: gyro output and temperatures at the scenario's rate, with known truth",
      studies::simulate_option_table(), [](const auto& o) {
    const sim::SimulationRun r = sim::simulate_to_files(studies::simulate_request(o));
    return print_report(o.json, sim::simulation_json(r), sim::simulation_text(r));
  });
}

}  // namespace gyrotherm::app
