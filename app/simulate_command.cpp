// gyrotherm simulate SCENARIO.toml [--rig R.toml] [--gyro G.toml] [--seed N]
//                    [--hidden TERM=COEF ...] -o OUT.csv [--json]

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.h"
#include "sim/config_loader.h"
#include "sim/effects/effect.h"
#include "sim/output.h"
#include "sim/simulator.h"

namespace gyrotherm::app {
namespace {

struct SimulateOptions {
  std::string scenario;
  std::string rig;
  std::string gyro;
  std::optional<std::uint64_t> seed;
  std::vector<std::string> hidden;
  std::string output;
  std::string plot;
  bool json = false;
};

int run_simulate(const SimulateOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  sim::Scenario scenario = sim::load_scenario(o.scenario);
  if (!o.rig.empty()) scenario.rig_file = o.rig;
  if (!o.gyro.empty()) scenario.gyro_file = o.gyro;
  if (o.seed) scenario.seed = *o.seed;
  const sim::RigConfig rig = sim::load_rig(scenario.rig_file);
  sim::GyroConfig gyro = sim::load_gyro(scenario.gyro_file);
  sim::check_scenario_against_rig(scenario, rig, scenario.rig_file);
  for (const std::string& h : o.hidden) sim::apply_hidden_option(gyro, h);

  const sim::Simulator simulator(scenario, rig, gyro);
  const sim::SimulationResult result = simulator.run();
  sim::write_simulation(o.output, simulator, result);
  if (!o.plot.empty()) sim::plot_simulation(o.plot, simulator, result);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  const auto& temp = result.truth.node(sim::RigDynamics::anode);
  const auto [tmin, tmax] = std::minmax_element(temp.begin(), temp.end());
  const double soak_error = sim::soak_control_error_c(simulator.scenario(), result.truth);
  const std::string truth_file = sim::truth_path_for(o.output).string();
  const double hours = result.time_s.back() / 3600.0;

  if (o.json) {
    nlohmann::ordered_json j;
    j["csv"] = o.output;
    j["truth"] = truth_file;
    j["scenario"] = scenario.name;
    j["seed"] = scenario.seed;
    j["rows"] = result.rows();
    j["duration_s"] = result.time_s.back();
    j["gyro_temp_min_c"] = *tmin;
    j["gyro_temp_max_c"] = *tmax;
    j["soak_control_error_c"] = soak_error;
    j["solver"] = {{"steps", result.solver.steps},
                   {"rhs_evaluations", result.solver.rhs_evaluations},
                   {"restarts", result.solver.restarts}};
    j["energy_residual_j"] = result.energy.residual_j();
    j["seconds"] = seconds;
    fmt::print("{}\n", j.dump());
    return 0;
  }
  fmt::print("simulated '{}' (seed {}): {} rows at {} Hz over {:.1f} h\n", scenario.name,
             scenario.seed, result.rows(), scenario.sample_rate_hz, hours);
  fmt::print("  gyro block (true, sensor side): {:.2f} .. {:.2f} °C\n", *tmin, *tmax);
  if (scenario.chamber)
    fmt::print("  chamber control in soaks (after 10 min): within ±{:.3f} °C\n", soak_error);
  else
    fmt::print("  no chamber: the INS sits in a {:.1f} °C room\n", scenario.room_c);
  std::string hidden;
  for (const effects::Effect* e : effects::registry())
    if (const double c = gyro.coefficient_of(*e); e->hidden() && c != 0.0)
      hidden += fmt::format("{}{}={:g}", hidden.empty() ? "" : ", ", e->name, c);
  fmt::print("  hidden effects: {}\n", hidden.empty() ? "none" : hidden);
  fmt::print("  CVODE: {} steps, {} right-hand-side evaluations, {} restarts; energy balance "
             "residual {:.2g} J\n",
             result.solver.steps, result.solver.rhs_evaluations, result.solver.restarts,
             result.energy.residual_j());
  fmt::print("wrote {} and {}{} in {:.2f} s\n", o.output, truth_file,
             o.plot.empty() ? "" : " and " + o.plot, seconds);
  return 0;
}

}  // namespace

void add_simulate_command(CLI::App& app, Run* run) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Simulate a thermal test: 1 Hz gyro output and temperatures with known truth");
  cmd->add_option("scenario", options->scenario, "Scenario file (scenarios/*.toml)")->required();
  cmd->add_option("--rig", options->rig, "Rig file (overrides the scenario's)");
  cmd->add_option("--gyro", options->gyro, "Gyro file (overrides the scenario's)");
  cmd->add_option("--seed", options->seed, "Noise seed (overrides the scenario's)");
  cmd->add_option("--hidden", options->hidden,
                  "Hidden effect TERM=COEF, repeatable; TERM one of " + effects::hidden_names())
      ->take_all();
  cmd->add_option("-o,--output", options->output, "Output CSV (a .truth.json goes beside it)")
      ->required();
  cmd->add_option("--plot", options->plot,
                  "Also draw temperatures and 100 s averages of the output into this PNG");
  cmd->add_flag("--json", options->json, "Print one JSON object instead of text");
  cmd->callback([options, run] { *run = [options] { return run_simulate(*options); }; });
}

}  // namespace gyrotherm::app
