// Simulator benchmarks: what a user waits for when simulating a shipped
// profile at 1 Hz, bias and noise included, in memory (no file writing).
// Counters: CVODE steps and right-hand-side evaluations, rows produced.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "sim/config_loader.h"
#include "sim/simulator.h"

namespace {

using namespace gyrotherm::sim;

Simulator load(const std::string& name) {
  const std::string dir = std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/";
  Scenario scenario = load_scenario(dir + name + ".toml");
  return Simulator(scenario, load_rig(scenario.rig_file), load_gyro(scenario.gyro_file));
}

void BM_SimulateProfile(benchmark::State& state, const std::string& name) {
  const Simulator simulator = load(name);
  SimulationResult result;
  for (auto _ : state) {
    result = simulator.run();
    benchmark::DoNotOptimize(result.gyro_dph.data());
  }
  state.counters["rows"] = static_cast<double>(result.rows());
  state.counters["simulated_h"] = result.time_s.back() / 3600.0;
  state.counters["cvode_steps"] = static_cast<double>(result.solver.steps);
  state.counters["rhs_evals"] = static_cast<double>(result.solver.rhs_evaluations);
  state.counters["restarts"] = static_cast<double>(result.solver.restarts);
}

void BM_ThermalOnly(benchmark::State& state, const std::string& name) {
  const Simulator simulator = load(name);
  for (auto _ : state) {
    ThermalTrace trace = simulator.run_thermal();
    benchmark::DoNotOptimize(trace.time_s.data());
  }
}

// The fastest repetition too: on a shared host a run is slowed, never sped up.
double least(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

BENCHMARK_CAPTURE(BM_SimulateProfile, cycle, std::string("cycle"))->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", least);
BENCHMARK_CAPTURE(BM_SimulateProfile, random_72h, std::string("random"))->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", least);
BENCHMARK_CAPTURE(BM_SimulateProfile, warmup, std::string("warmup"))->Unit(benchmark::kMillisecond)->UseRealTime()->ComputeStatistics("min", least);
BENCHMARK_CAPTURE(BM_ThermalOnly, random_72h, std::string("random"))->Unit(benchmark::kMillisecond)->ComputeStatistics("min", least);

}  // namespace

BENCHMARK_MAIN();
