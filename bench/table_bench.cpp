// A record handed over as arrays (fit/data/table.h: what the Python binding
// passes, numpy columns never copied).
//  BM_FitTable: fit::prepare_table (one pass over the caller's columns) and
//    fit_model (ols, B = b0 + T + T^2 + dT) on 10⁷ samples at 1 Hz (116 days)
//    held in three std::vectors (240 MB), made once outside the timed loop by
//    table_record() below from seed 1 (no CVODE): the same arrays a Python
//    script can make to time its own fit against this one.
//    Counters: rows; rss_growth_mb, the peak resident memory while preparing
//    and fitting over the resident memory with the arrays made (the peak
//    reset through /proc/self/clear_refs, peak_reset = 1; the target is
//    ≤ 64 MB), rss_growth_prepare_mb the same after prepare_table alone;
//    and the fitted coefficients (b0, T, T^2, dT), to check the
//    other side's fit against.
//    With GYROTHERM_BENCH_TABLE=FILE set, the arrays are read instead from
//    FILE: rows of three float64 (time s, temperature °C, gyro °/h), as
//    bench/python_fit_bench.py writes the arrays it times gyrotherm.fit on.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "fit/data/table.h"
#include "fit/engines/engine.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "studies/fit/fit_run.h"
#include "studies/options/fit_options.h"

namespace {

using namespace gyrotherm;

// The record: sample k at t_k = k s; a chamber cycling ±30 °C about 20 °C every
// 6 h, T_k = 20 + 30 sin(ω t_k), ω = 2π/21600 s; the gyro
//   g_k = −7 − 0.03 T_k + 0.001 T_k² + 20 · 30 ω cos(ω t_k) + e_k  (°/h),
// e_k white noise of σ 0.5 °/h (std::normal_distribution on std::mt19937_64
// seeded with `seed`), and a glitch of +25 °/h every 100 003rd sample.
struct TableRecord {
  std::vector<double> time_s, temp_c, gyro_dph;
  explicit TableRecord(std::size_t rows, unsigned seed = 1) : time_s(rows), temp_c(rows), gyro_dph(rows) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.5);
    const double w = 2.0 * M_PI / 21600.0;
    for (std::size_t k = 0; k < rows; ++k) {
      const double t = static_cast<double>(k);
      time_s[k] = t;
      temp_c[k] = 20.0 + 30.0 * std::sin(w * t);
      gyro_dph[k] = -7.0 - 0.03 * temp_c[k] + 0.001 * temp_c[k] * temp_c[k] + 20.0 * 30.0 * w * std::cos(w * t) +
                    noise(rng) + (k % 100003 == 0 ? 25.0 : 0.0);
    }
  }
  // The rows of a raw file of float64 triples (time, temperature, gyro).
  explicit TableRecord(const std::string& raw) {
    std::ifstream in(raw, std::ios::binary);
    std::vector<double> all;
    for (double v[3]; in.read(reinterpret_cast<char*>(v), sizeof v);) all.insert(all.end(), v, v + 3);
    for (std::size_t k = 0; k + 2 < all.size(); k += 3) {
      time_s.push_back(all[k]);
      temp_c.push_back(all[k + 1]);
      gyro_dph.push_back(all[k + 2]);
    }
  }
  fit::Table table() const {
    return {"bench arrays",
            {{"time_s", time_s.data(), time_s.size()},
             {"temp_c", temp_c.data(), temp_c.size()},
             {"gyro_dph", gyro_dph.data(), gyro_dph.size()}}};
  }
};

// A field of /proc/self/status in MB ("VmRSS", "VmHWM"), or -1.
double status_mb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1)) / 1024.0;  // kB
  return -1.0;
}

// Resets the peak resident memory to the current one (Linux ≥ 4.0); false where it cannot.
bool reset_peak_rss() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return clear.good();
}

// The process's peak resident memory since the reset (or since it started), MB.
double peak_rss_mb() {
  if (const double hwm = status_mb("VmHWM"); hwm >= 0.0) return hwm;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
}

// The record a benchmark fits: read from GYROTHERM_BENCH_TABLE when set, else
// made with state.range(0) rows.
TableRecord bench_record(const benchmark::State& state) {
  const char* raw = std::getenv("GYROTHERM_BENCH_TABLE");
  return raw != nullptr ? TableRecord(std::string(raw)) : TableRecord(static_cast<std::size_t>(state.range(0)));
}

// The fitted coefficients as counters: b0 and one per term.
void coefficient_counters(benchmark::State& state, const fit::ModelFit& result,
                          const std::vector<const fit::Term*>& terms) {
  state.counters["b0"] = result.coefficients.intercept;
  for (std::size_t k = 0; k < terms.size(); ++k) state.counters[std::string(terms[k]->name)] = result.coefficients.b[k];
}

void BM_FitTable(benchmark::State& state) {
  const TableRecord record = bench_record(state);
  const std::size_t rows = record.time_s.size();
  const fit::Table table = record.table();
  const std::vector<const fit::Term*> terms = fit::parse_formula("T + T^2 + dT");
  const fit::EngineInfo& ols = fit::find_engine("ols");
  const fit::PipelineOptions options;
  // The growth over the resident memory with the arrays made: from the peak
  // reset to it where the kernel allows, else from the peak so far (then
  // exact only on the first run in the process).
  const bool reset = reset_peak_rss();
  const double before_mb = reset ? status_mb("VmRSS") : peak_rss_mb();
  fit::ModelFit result;
  double prepared_mb = 0.0;
  for (auto _ : state) {
    const fit::PreparedData data = fit::prepare_table(table, options);
    prepared_mb = peak_rss_mb() - before_mb;
    result = fit::fit_model(data, terms, ols, {});
    benchmark::DoNotOptimize(result.coefficients.b.data());
  }
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["rss_growth_mb"] = peak_rss_mb() - before_mb;
  state.counters["rss_growth_prepare_mb"] = prepared_mb;
  state.counters["peak_reset"] = reset ? 1.0 : 0.0;
  coefficient_counters(state, result, terms);
}

BENCHMARK(BM_FitTable)->Arg(10'000'000)->Iterations(1)->Unit(benchmark::kSecond);

// The library's whole `fit` on the table (studies::run_fit, the call
// gyrotherm.fit makes): the command's defaults, model T + T^2 + dT, the JSON
// and the windows' report included. Same record and counters as BM_FitTable
// but rss_growth_prepare_mb.
void BM_RunFitTable(benchmark::State& state) {
  const TableRecord record = bench_record(state);
  const fit::Table table = record.table();
  studies::FitCommandOptions options;
  options.data = "arrays";
  options.model.model = "T + T^2 + dT";
  const studies::FitRequest request = studies::fit_request(options);
  const bool reset = reset_peak_rss();
  const double before_mb = reset ? status_mb("VmRSS") : peak_rss_mb();
  studies::FitRun run;
  for (auto _ : state) {
    run = studies::run_fit(request, table);
    benchmark::DoNotOptimize(run.json.data());
  }
  state.counters["rows"] = static_cast<double>(record.time_s.size());
  state.counters["rss_growth_mb"] = peak_rss_mb() - before_mb;
  state.counters["peak_reset"] = reset ? 1.0 : 0.0;
  coefficient_counters(state, run.channels.front().result, request.terms);
}

BENCHMARK(BM_RunFitTable)->Arg(10'000'000)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
