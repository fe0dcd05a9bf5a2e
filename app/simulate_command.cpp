// gyrotherm simulate SCENARIO.toml [--rig R.toml] [--gyro G.toml] [--seed N]
//                    [--hidden TERM=COEF ...] -o OUT.csv [--plot PNG] [--json]
// (studies/options/simulate_options.h, sim/simulation_run.h)

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/simulate_options.h"

namespace gyrotherm::app {

void add_simulate_command(CLI::App& app, Run* run) {
  CLI::App* cmd = add_subcommand(
      app, "simulate",
      "Simulate a thermal test: gyro output and temperatures at the scenario's rate, with known truth");
  bind_command<studies::SimulateCommandOptions>(cmd, run, studies::simulate_option_table(), [](const auto& o) {
    const sim::SimulationRun r = sim::simulate_to_files(studies::simulate_request(o));
    fmt::print("{}", o.json ? sim::simulation_json(r).dump() + "\n" : sim::simulation_text(r));
    return 0;
  });
}

}  // namespace gyrotherm::app
