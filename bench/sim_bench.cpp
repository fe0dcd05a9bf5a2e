// Simulator benchmarks: what a user waits for when simulating a shipped
// profile at 1 Hz, bias and noise included, in memory (no file writing).
// Counters: CVODE steps and right-hand-side evaluations, rows produced.

#include <benchmark/benchmark.h>

#include <string>

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

BENCHMARK_CAPTURE(BM_SimulateProfile, cycle, std::string("cycle"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateProfile, random_72h, std::string("random"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SimulateProfile, warmup, std::string("warmup"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ThermalOnly, random_72h, std::string("random"))->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
