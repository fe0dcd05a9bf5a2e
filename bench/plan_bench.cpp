// `gyrotherm plan`'s speed (issue aim: a plan for a model of up to six terms
// in ≤ 60 s on two cores): the whole plan (the six standard recipes' searches
// and the planned profile's, with its figure and files), for the paper's
// model and for six terms, and one prediction (thermal path, windows,
// sandwich) on the 8.8 h cycle, the unit every search is made of.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "studies/plan/plan.h"
#include "studies/plan/plan_setup.h"

namespace {

using namespace gyrotherm::studies::plan;

PlanRequest request(int terms) {
  PlanRequest rq;
  rq.scenario = std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/cycle.toml";
  rq.out = (std::filesystem::temp_directory_path() / "gyrotherm_bench_plan").string();
  if (terms == 6) {
    rq.model = "T + T^2 + T^3 + dT + T*dT + d2T";
    rq.se = {"T^3=1e-8", "T*dT=0.01", "d2T=100"};  // met in ≈ 11 h; T, T^2, dT reported
  }
  return rq;
}

void BM_Plan(benchmark::State& state) {
  const PlanRequest rq = request(static_cast<int>(state.range(0)));
  PlanResult r;
  for (auto _ : state) r = run_plan(rq);
  state.counters["evaluations"] = static_cast<double>(r.evaluations);
  state.counters["planned_h"] = r.duration_s / 3600.0;
  state.counters["ms_per_evaluation"] = 1e3 * r.seconds / static_cast<double>(r.evaluations);
  std::filesystem::remove_all(rq.out);
}
BENCHMARK(BM_Plan)->Arg(3)->Arg(6)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

void BM_PredictPrecision(benchmark::State& state) {
  const PlanSetup s = plan_setup(request(static_cast<int>(state.range(0))));
  gyrotherm::sim::Scenario predicted = s.base;
  predicted.sample_rate_hz = kPredictionRateHz;
  const DesignEvaluator ev(predicted, s.rig, s.gyro, s.noise, s.model);
  const ChamberProfile cycle{s.base.start_c, s.base.segments};
  for (auto _ : state) benchmark::DoNotOptimize(ev.precision(cycle));
}
BENCHMARK(BM_PredictPrecision)->Arg(3)->Arg(6)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
