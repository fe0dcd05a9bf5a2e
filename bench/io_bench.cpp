// CSV input and output, in bytes per second, on a simulated 72 h run (Test 1,
// scenarios/random.toml: 260 k rows of time, four temperatures, the gyro
// output and the true bias; about 20 MB). The simulation and the file are
// made once, outside the timed loops.
//  BM_ReadMeasurementCsv: fit::read_measurement_csv of that file (what fit,
//    compensate and diagnose wait for).
//  BM_FormatSimulationCsv: sim::simulation_csv, the text in memory.
//  BM_WriteSimulationCsv: sim::simulation_csv and writing it to a file.

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "fit/data/measurement.h"
#include "sim/config_loader.h"
#include "sim/output.h"
#include "sim/simulator.h"

namespace {

using namespace gyrotherm;

struct Run72h {
  sim::Simulator simulator;
  sim::SimulationResult result;
  std::filesystem::path csv;
  std::size_t csv_bytes = 0;

  static sim::Simulator make() {
    const sim::Scenario sc = sim::load_scenario(std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/random.toml");
    return sim::Simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(sc.gyro_file));
  }
  Run72h()
      : simulator(make()),
        result(simulator.run()),
        csv(std::filesystem::temp_directory_path() / ("gyrotherm_io_bench_" + std::to_string(::getpid()) + ".csv")) {
    sim::write_simulation(csv, simulator, result);
    csv_bytes = static_cast<std::size_t>(std::filesystem::file_size(csv));
  }
  ~Run72h() {
    std::error_code ignored;
    std::filesystem::remove(csv, ignored);
    std::filesystem::remove(sim::truth_path_for(csv), ignored);
  }
};

const Run72h& run72h() {
  static const Run72h run;
  return run;
}

void BM_ReadMeasurementCsv(benchmark::State& state) {
  const Run72h& run = run72h();
  for (auto _ : state) {
    const fit::Measurement m = fit::read_measurement_csv(run.csv);
    benchmark::DoNotOptimize(m.gyro_dph.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(run.csv_bytes));
  state.counters["rows"] = static_cast<double>(run.result.rows());
  state.counters["file_mb"] = static_cast<double>(run.csv_bytes) / 1e6;
}

void BM_FormatSimulationCsv(benchmark::State& state) {
  const Run72h& run = run72h();
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string text = sim::simulation_csv(run.simulator, run.result);
    bytes = text.size();
    benchmark::DoNotOptimize(text.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(bytes));
  state.counters["rows"] = static_cast<double>(run.result.rows());
}

void BM_WriteSimulationCsv(benchmark::State& state) {
  const Run72h& run = run72h();
  const std::filesystem::path out = run.csv.string() + ".out";
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string text = sim::simulation_csv(run.simulator, run.result);
    std::ofstream file(out, std::ios::binary | std::ios::trunc);
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    file.close();
    bytes = text.size();
  }
  std::error_code ignored;
  std::filesystem::remove(out, ignored);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(bytes));
  state.counters["rows"] = static_cast<double>(run.result.rows());
}

BENCHMARK(BM_ReadMeasurementCsv)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FormatSimulationCsv)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WriteSimulationCsv)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
