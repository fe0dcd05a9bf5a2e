// Diagnosis benchmarks (the limits: diagnose on the 72 h record
// ≤ 1.5 s, on a 10-day record ≤ 5 s, the calibration by simulation included).
//  BM_Diagnose/<record>: studies::diagnose with its defaults (every registry
//    candidate, the step family, the parametric bootstrap) on the record
//    prepared once (100 s windows): random_72h is scenarios/random.toml
//    (2593 windows); ten_days the same profile with its holds 3.6 × as long
//    (about 10 days).
//  BM_Fit/<record>: fit_model (ols with its intervals) on the same record,
//    the figure diagnose's time is read against.

#include <benchmark/benchmark.h>

#include <string>

#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "sim/config_loader.h"
#include "sim/simulator.h"
#include "studies/diagnose/diagnosis.h"

namespace {

using namespace gyrotherm;

fit::PreparedData prepared(double hold_factor) {
  sim::Scenario sc = sim::load_scenario(std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/random.toml");
  for (sim::Segment& s : sc.segments)
    if (s.kind == sim::SegmentKind::hold) s.duration_s *= hold_factor;
  const sim::SimulationResult r = sim::Simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(sc.gyro_file)).run();
  fit::Measurement m;
  m.file = "random";
  m.time_s = r.time_s;
  m.temp_c = r.temp_c;
  m.gyro_dph = r.gyro_dph;
  return fit::prepare_data(m, {});
}

const fit::PreparedData& record(const std::string& name) {
  static const fit::PreparedData random_72h = prepared(1.0);
  static const fit::PreparedData ten_days = prepared(3.6);
  return name == "ten_days" ? ten_days : random_72h;
}

void BM_Diagnose(benchmark::State& state, const std::string& name) {
  const fit::PreparedData& data = record(name);
  const auto terms = fit::parse_formula("T + T^2 + dT");
  for (auto _ : state) benchmark::DoNotOptimize(studies::diagnose(data, terms, fit::find_engine("ols"), {}));
  state.counters["windows"] = static_cast<double>(data.series.size());
}

void BM_Fit(benchmark::State& state, const std::string& name) {
  const fit::PreparedData& data = record(name);
  const auto terms = fit::parse_formula("T + T^2 + dT");
  for (auto _ : state) benchmark::DoNotOptimize(fit::fit_model(data, terms, fit::find_engine("ols"), {}));
  state.counters["windows"] = static_cast<double>(data.series.size());
}

}  // namespace

BENCHMARK_CAPTURE(BM_Diagnose, random_72h, std::string("random_72h"))->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Diagnose, ten_days, std::string("ten_days"))->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Fit, random_72h, std::string("random_72h"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Fit, ten_days, std::string("ten_days"))->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
