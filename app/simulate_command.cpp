// gyrotherm simulate SCENARIO.toml [--rig R.toml] [--gyro G.toml] [--seed N]
//                    [--hidden TERM=COEF ...] -o OUT.csv [--plot PNG] [--json]
// (sim/simulation_run.h)

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "app/commands.h"
#include "sim/effects/effect.h"
#include "sim/simulation_run.h"

namespace gyrotherm::app {

void add_simulate_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<sim::SimulateRequest>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Simulate a thermal test: gyro output and temperatures at the scenario's rate, with known truth");
  cmd->add_option("scenario", o->scenario, "Scenario file (scenarios/*.toml)")->required();
  cmd->add_option("--rig", o->rig, "Rig file (overrides the scenario's)");
  cmd->add_option("--gyro", o->gyro, "Gyro file (overrides the scenario's)");
  cmd->add_option("--seed", o->seed, "Noise seed (overrides the scenario's)");
  cmd->add_option("--hidden", o->hidden, "Hidden effect TERM=COEF, repeatable; TERM one of " + effects::hidden_names())
      ->take_all();
  cmd->add_option("-o,--output", o->output, "Output CSV (a .truth.json goes beside it)")->required();
  cmd->add_option("--plot", o->plot, "Also draw temperatures and 100 s averages of the output into this PNG");
  cmd->add_flag("--json", *json, "Print one JSON object instead of text");
  when_chosen(cmd, run, [o, json] {
    const sim::SimulationRun r = sim::simulate_to_files(*o);
    fmt::print("{}", *json ? sim::simulation_json(r).dump() + "\n" : sim::simulation_text(r));
    return 0;
  });
}

}  // namespace gyrotherm::app
