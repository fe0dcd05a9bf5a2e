#pragma once
// `gyrotherm simulate`: a scenario with its rig and gyro (each file may be
// overridden), the hidden effects of --hidden, run and written beside its
// truth (sim/output.h), with an optional figure; and the run's summary for
// the terminal and for --json.

#include <cstdint>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sim/simulator.h"

namespace gyrotherm::sim {

struct SimulateRequest {
  std::string scenario;              // SCENARIO.toml
  std::string rig, gyro;             // override the scenario's files ("" keeps them)
  std::optional<std::uint64_t> seed;  // overrides the scenario's
  std::vector<std::string> hidden;   // TERM=COEF
  std::string output;                // OUT.csv (the truth goes beside it)
  std::string plot;                  // a PNG, or ""
};

struct SimulationRun {
  SimulateRequest request;
  Scenario scenario;
  std::string truth_file;
  std::size_t rows = 0;
  double duration_s = 0.0;
  double gyro_temp_min_c = 0.0, gyro_temp_max_c = 0.0;
  double soak_control_error_c = 0.0;
  SolverStatistics solver;
  double energy_residual_j = 0.0;
  std::string hidden;  // "grad=0.02, T^3=1e-07", or "" for none
  std::string format = "CSV";         // the record's (sim/record_format.h): "CSV", "PX4 ULog", ...
  std::vector<std::string> channels;  // beside the gyro: "gyro y", "accel x", "baro"
  double seconds = 0.0;
};

// A run in memory: the simulator (its scenario, rig and gyro as used), the
// record and the summary; request.output and request.plot are not used.
struct Simulation {
  std::unique_ptr<Simulator> simulator;
  SimulationResult result;
  SimulationRun run;  // truth_file empty
};
// Throws InputError on a bad file or option.
Simulation simulate(const SimulateRequest& request);

// simulate(), then the CSV and its truth (and the figure) written.
// Throws InputError (nothing written) on a bad file or option.
SimulationRun simulate_to_files(const SimulateRequest& request);
// simulate --json: csv (the output, whatever its format), truth, scenario,
// seed, rows, duration_s, gyro_temp_min_c, gyro_temp_max_c,
// soak_control_error_c, solver, energy_residual_j, seconds; format when the
// output is not a CSV, and channels when the gyro file has any.
nlohmann::ordered_json simulation_json(const SimulationRun& run);
std::string simulation_text(const SimulationRun& run);

}  // namespace gyrotherm::sim
