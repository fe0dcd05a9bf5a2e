// CSV input and output, in bytes per second, on a simulated 72 h run (Test 1,
// scenarios/random.toml: 260 k rows of time, four temperatures, the gyro
// output and the true bias; about 20 MB). The simulation and the file are
// made once, outside the timed loops.
//  BM_ReadMeasurementCsv: fit::read_measurement_csv of that file (what fit,
//    compensate and diagnose wait for).
//  BM_FormatSimulationCsv: sim::simulation_csv, the text in memory.
//  BM_WriteSimulationCsv: sim::simulation_csv and writing it to a file.
//
// With GYROTHERM_LARGE_CSV naming a large log (scripts/large_input.sh: the
// 557 MB, 10-day record at 10 Hz), three more on that file, from the page
// cache, one iteration each, so the distance of `fit` to each limit shows:
//  BM_LargeLog_Read: the bytes read in 1 MB blocks, nothing done with them;
//  BM_LargeLog_Parse: fit::for_each_row on one thread, the rows summed;
//  BM_LargeLog_Prepare: fit::prepare_csv alone (one pass, fit/data/streaming.h:
//    blocks parsed on one thread per core, glitch filter and windows on another);
//  BM_LargeLog_Filter: the preparing thread's work alone, on the rows already
//    parsed into arrays (fit::prepare_table, the same one-pass preparer);
//  BM_LargeLog_Fit: what `gyrotherm fit` does, fit::prepare_csv and the ols
//    fit of T + T^2 + dT (its intervals as the command's, a bootstrap where
//    the record's noise is random-walk dominated).

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fit/data/measurement.h"
#include "fit/data/streaming.h"
#include "fit/data/table.h"
#include "fit/engines/engine.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"
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

void set_large_counters(benchmark::State& state, const std::filesystem::path& csv) {
  const auto bytes = static_cast<std::int64_t>(std::filesystem::file_size(csv));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * bytes);
  state.counters["file_mb"] = static_cast<double>(bytes) / 1e6;
}

void BM_LargeLog_Read(benchmark::State& state, const std::filesystem::path& csv) {
  std::vector<char> block(std::size_t{1} << 20);
  for (auto _ : state) {
    std::FILE* f = std::fopen(csv.c_str(), "rb");
    std::size_t total = 0;
    for (std::size_t got; (got = std::fread(block.data(), 1, block.size(), f)) > 0;) total += got;
    std::fclose(f);
    benchmark::DoNotOptimize(total);
  }
  set_large_counters(state, csv);
}

void BM_LargeLog_Parse(benchmark::State& state, const std::filesystem::path& csv) {
  for (auto _ : state) {
    double sum = 0.0;
    const fit::CsvHeader h = fit::for_each_row(csv, fit::ColumnMap{}, [&](double t, double temp, double gyro, double temp2) {
      sum += t + temp + gyro + temp2;
    });
    benchmark::DoNotOptimize(sum);
    state.counters["rows"] = static_cast<double>(h.rows);
  }
  set_large_counters(state, csv);
}

void BM_LargeLog_Prepare(benchmark::State& state, const std::filesystem::path& csv) {
  for (auto _ : state) {
    const fit::PreparedData d = fit::prepare_csv(csv, fit::PipelineOptions{});
    benchmark::DoNotOptimize(d.series.gyro_dph.data());
    state.counters["windows"] = static_cast<double>(d.series.size());
  }
  set_large_counters(state, csv);
}

void BM_LargeLog_Filter(benchmark::State& state, const std::filesystem::path& csv) {
  const fit::Measurement m = fit::read_measurement_csv(csv);
  fit::Table table;
  table.columns = {{"time_s", m.time_s.data(), m.size()}, {"temp_c", m.temp_c.data(), m.size()},
                   {"gyro_dph", m.gyro_dph.data(), m.size()}};
  if (m.has_temp2()) table.columns.push_back({"temp2_c", m.temp2_c.data(), m.size()});
  for (auto _ : state) {
    const fit::PreparedData d = fit::prepare_table(table, fit::PipelineOptions{});
    benchmark::DoNotOptimize(d.series.gyro_dph.data());
  }
  set_large_counters(state, csv);
}

void BM_LargeLog_Fit(benchmark::State& state, const std::filesystem::path& csv) {
  const auto terms = fit::parse_formula("T + T^2 + dT");
  const fit::EngineInfo& ols = fit::find_engine("ols");
  for (auto _ : state) {
    bool streamed = false;
    const fit::PreparedData d = fit::prepare_csv(csv, fit::PipelineOptions{}, &streamed);
    const fit::ModelFit f = fit::fit_model(d, terms, ols, fit::EngineSettings{});
    benchmark::DoNotOptimize(f.instability_after_dph);
    state.counters["windows"] = static_cast<double>(d.series.size());
    state.counters["streamed"] = streamed ? 1.0 : 0.0;
  }
  set_large_counters(state, csv);
}

BENCHMARK(BM_ReadMeasurementCsv)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FormatSimulationCsv)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WriteSimulationCsv)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  if (const char* large = std::getenv("GYROTHERM_LARGE_CSV"); large != nullptr && *large != 0) {
    const std::filesystem::path csv = large;
    if (!std::filesystem::exists(csv)) {
      std::fprintf(stderr, "GYROTHERM_LARGE_CSV=%s: no such file\n", large);
      return 2;
    }
    for (auto [name, fn] : {std::pair{"BM_LargeLog_Read", &BM_LargeLog_Read},
                            std::pair{"BM_LargeLog_Parse", &BM_LargeLog_Parse},
                            std::pair{"BM_LargeLog_Prepare", &BM_LargeLog_Prepare},
                            std::pair{"BM_LargeLog_Filter", &BM_LargeLog_Filter},
                            std::pair{"BM_LargeLog_Fit", &BM_LargeLog_Fit}})
      benchmark::RegisterBenchmark(name, fn, csv)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
