#pragma once
// The paper's experiments on the simulated gyro (`gyrotherm reproduce`):
//
//  1. simulate the −40..60 °C cycle, Test 1's random profile and Test 2's
//     natural warm-up (scenarios/cycle.toml, random.toml, warmup.toml), each
//     with the seed its scenario names (or an override);
//  2. on the cycle: the raw instability, and a fit of the paper's model
//     T + T^2 + dT with every engine (instability after, ratio,
//     coefficients, error against the truth, evaluations, time);
//  3. each engine's cycle fit applied to Test 1 and Test 2 with the causal,
//     real-time compensator (backward differences, only completed windows),
//     as the paper did: instability before and after, and the ratio.
//
// Everything is computed in memory; report.h writes the tables and figures,
// describing each test by the scenario that ran (ScenarioFacts).

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "fit/compensation.h"
#include "fit/pipeline.h"
#include "studies/simulated.h"
#include "sim/simulator.h"

namespace gyrotherm::studies {

struct ReproduceOptions {
  std::filesystem::path cycle, test1, test2;  // scenario files
  std::vector<std::string> engines;           // empty: every registered engine
  std::uint64_t engine_seed = 1;
  // Called with a short description of each step and its fraction done:
  // reproduce() reaches kReproduceComputedShare, write_reproduce_report()
  // (report.h) the rest, and "done" at 1 once every file is written.
  std::function<void(const std::string& step, double fraction)> progress;
};
inline constexpr double kReproduceComputedShare = 0.9;

// What the report says about a scenario, read from the scenario that ran
// rather than written into the report by hand.
struct ScenarioFacts {
  double duration_h = 0.0;                     // the profile's length
  double room_c = 23.0;
  bool chamber = true;                         // false: the INS sits in the room
  double set_min_c = 0.0, set_max_c = 0.0;     // the chamber's set points (chamber only)
  double gyro_min_c = 0.0, gyro_max_c = 0.0;   // the gyro temperature logged
  // "in the chamber, set points -20..60 °C, 72.3 h" or "in a 23 °C room, 8 h".
  std::string text() const;
};

struct EngineOnCycle {
  std::string engine;
  fit::ModelFit fit;
  std::map<std::string, double> coefficient_error;  // relative, against the truth
};

struct TestOutcome {
  std::string name;               // "test1" or "test2"
  std::uint64_t seed = 0;
  ScenarioFacts facts;
  double before_dph = 0.0;
  std::map<std::string, fit::Compensation> by_engine;  // causal compensation with each engine's cycle fit
};

struct ReproduceResult {
  std::uint64_t cycle_seed = 0;
  ScenarioFacts cycle_facts;
  sim::SimulationResult cycle_run, test1_run, test2_run;
  fit::PreparedData cycle_data;
  Truth truth;
  double cycle_raw_dph = 0.0;
  std::vector<EngineOnCycle> engines;
  TestOutcome test1, test2;
  double seconds = 0.0;
};

ReproduceResult reproduce(const ReproduceOptions& options);

// The paper's Table 1 figures (°/h).
struct PaperFigures {
  double cycle_raw = 0.00953, cycle_stepwise = 0.00219, cycle_iafsa = 0.00185;
  double test1_before = 0.0159, test1_after = 0.00201, test1_times = 7.91;
  double test2_before = 0.0025, test2_after = 0.0016, test2_times = 1.56;
};

}  // namespace gyrotherm::studies
