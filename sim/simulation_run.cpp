#include "sim/simulation_run.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>

#include "sim/config_loader.h"
#include "sim/output.h"
#include "sim/record_format.h"

namespace gyrotherm::sim {

Simulation simulate(const SimulateRequest& o) {
  const auto started = std::chrono::steady_clock::now();
  Simulation s;
  SimulationRun& run = s.run;
  run.request = o;
  Scenario scenario = load_scenario(o.scenario);
  if (!o.rig.empty()) scenario.rig_file = o.rig;
  if (!o.gyro.empty()) scenario.gyro_file = o.gyro;
  if (o.seed) scenario.seed = *o.seed;
  const RigConfig rig = load_rig(scenario.rig_file);
  GyroConfig gyro = load_gyro(scenario.gyro_file);
  check_scenario_against_rig(scenario, rig, scenario.rig_file);
  for (const std::string& h : o.hidden) apply_hidden_option(gyro, h);
  if (!o.output.empty()) {
    const RecordFormat& format = record_format_for(o.output);
    format.check(gyro, scenario.gyro_file);  // before the run, not after it
    run.format = format.name;
  }
  for (const ChannelConfig& ch : gyro.channels) run.channels.push_back(ch.label());

  s.simulator = std::make_unique<Simulator>(scenario, rig, gyro);
  s.result = s.simulator->run();
  const SimulationResult& result = s.result;
  const auto& temp = result.truth.node(RigDynamics::anode);
  const auto [tmin, tmax] = std::minmax_element(temp.begin(), temp.end());
  run.scenario = s.simulator->scenario();
  run.rows = result.rows();
  run.duration_s = result.time_s.back();
  run.gyro_temp_min_c = *tmin;
  run.gyro_temp_max_c = *tmax;
  run.soak_control_error_c = soak_control_error_c(s.simulator->scenario(), result.truth);
  run.solver = result.solver;
  run.energy_residual_j = result.energy.residual_j();
  for (const effects::Effect* e : effects::registry())
    if (const double c = gyro.coefficient_of(*e); e->hidden() && c != 0.0)
      run.hidden += fmt::format("{}{}={:g}", run.hidden.empty() ? "" : ", ", e->name, c);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return s;
}

SimulationRun simulate_to_files(const SimulateRequest& o) {
  const auto started = std::chrono::steady_clock::now();
  Simulation s = simulate(o);
  write_simulation(o.output, *s.simulator, s.result);
  if (!o.plot.empty()) plot_simulation(o.plot, *s.simulator, s.result);
  s.run.truth_file = truth_path_for(o.output).string();
  s.run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return s.run;
}

nlohmann::ordered_json simulation_json(const SimulationRun& r) {
  nlohmann::ordered_json j;
  j["csv"] = r.request.output;
  j["truth"] = r.truth_file;
  j["scenario"] = r.scenario.name;
  j["seed"] = r.scenario.seed;
  j["rows"] = r.rows;
  j["duration_s"] = r.duration_s;
  j["gyro_temp_min_c"] = r.gyro_temp_min_c;
  j["gyro_temp_max_c"] = r.gyro_temp_max_c;
  j["soak_control_error_c"] = r.soak_control_error_c;
  j["solver"] = {{"steps", r.solver.steps},
                 {"rhs_evaluations", r.solver.rhs_evaluations},
                 {"restarts", r.solver.restarts}};
  j["energy_residual_j"] = r.energy_residual_j;
  j["seconds"] = r.seconds;
  if (r.format != "CSV") j["format"] = r.format;
  if (!r.channels.empty()) j["channels"] = r.channels;
  return j;
}

std::string simulation_text(const SimulationRun& r) {
  std::string out = fmt::format("simulated '{}' (seed {}): {} rows at {} Hz over {:.1f} h\n", r.scenario.name,
                                r.scenario.seed, r.rows, r.scenario.sample_rate_hz, r.duration_s / 3600.0);
  out += fmt::format("  gyro block (true, sensor side): {:.2f} .. {:.2f} °C\n", r.gyro_temp_min_c, r.gyro_temp_max_c);
  if (r.scenario.chamber)
    out += fmt::format("  chamber control in soaks (after 10 min): within ±{:.3f} °C\n", r.soak_control_error_c);
  else
    out += fmt::format("  no chamber: the INS sits in a {:.1f} °C room\n", r.scenario.room_c);
  out += fmt::format("  hidden effects: {}\n", r.hidden.empty() ? "none" : r.hidden);
  if (!r.channels.empty()) out += fmt::format("  channels beside the gyro: {}\n", fmt::join(r.channels, ", "));
  out += fmt::format(
      "  CVODE: {} steps, {} right-hand-side evaluations, {} restarts; energy balance residual {:.2g} J\n",
      r.solver.steps, r.solver.rhs_evaluations, r.solver.restarts, r.energy_residual_j);
  out += fmt::format("wrote {}{} and {}{} in {:.2f} s\n", r.request.output,
                     r.format == "CSV" ? "" : " (" + r.format + ")", r.truth_file,
                     r.request.plot.empty() ? "" : " and " + r.request.plot, r.seconds);
  return out;
}

}  // namespace gyrotherm::sim
