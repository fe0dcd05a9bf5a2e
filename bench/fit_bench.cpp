// Fitting benchmarks.
//  BM_ObjectiveGram / BM_ObjectiveNaive: one σ evaluation at l points, the
//    O(m²) Gram form engines use against forming every residual (O(l·m)).
//  BM_EngineToTarget/<engine>: the paper's model on the simulated cycle
//    (scenarios/cycle.toml, 100 s windows); each engine runs 10 seeds with the
//    target σ = optimum·(1 + 1e-6) and a budget of 200 000 evaluations.
//    Counters: median evaluations to the target, how many of the 10 reached
//    it; the time is for the 10 fits.
//  BM_CausalCompensate: the real-time compensator on 6, 24 and 72 h (below).
//  BM_FitIntervals: fit_model (ols, the paper's model) on the 72 h random
//    profile (scenarios/random.toml, 2593 windows), prepared once, with the
//    identified noise model's intervals; BM_IdentifyNoise: the REML
//    identification alone on the same problem (the share it costs).

#include <benchmark/benchmark.h>

#include <random>

#include "studies/allan/allan_study.h"

#include <algorithm>
#include <string>

#include "fit/model/formula.h"
#include "fit/causal_compensator.h"
#include "fit/engines/ols.h"
#include "fit/pipeline.h"
#include "sim/config_loader.h"
#include "sim/simulator.h"

namespace {

using namespace gyrotherm;

fit::LinearProblem synthetic(std::size_t l) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(l), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(l));
  for (Eigen::Index p = 0; p < x.rows(); ++p) {
    const double t = 20.0 + 40.0 * std::sin(0.001 * static_cast<double>(p)) + 0.1 * std::sin(0.37 * static_cast<double>(p));
    x(p, 0) = t;
    x(p, 1) = t * t;
    x(p, 2) = 0.04 * std::cos(0.001 * static_cast<double>(p));
    y[p] = -7.0 - 3e-4 * t + 1e-6 * t * t + 1.8 * x(p, 2) + 1e-3 * std::sin(1.7 * static_cast<double>(p));
  }
  return fit::LinearProblem(x, y, {"T", "T^2", "dT"});
}

void BM_ObjectiveGram(benchmark::State& state) {
  const fit::LinearProblem problem = synthetic(static_cast<std::size_t>(state.range(0)));
  const std::vector<double> z = {0.1, -0.2, 0.3};
  for (auto _ : state) benchmark::DoNotOptimize(problem.objective(z));
  state.counters["points"] = static_cast<double>(state.range(0));
}

void BM_ObjectiveNaive(benchmark::State& state) {
  const fit::LinearProblem problem = synthetic(static_cast<std::size_t>(state.range(0)));
  const std::vector<double> z = {0.1, -0.2, 0.3};
  for (auto _ : state) benchmark::DoNotOptimize(problem.objective_naive(z));
  state.counters["points"] = static_cast<double>(state.range(0));
}

BENCHMARK(BM_ObjectiveGram)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_ObjectiveNaive)->Arg(1000)->Arg(10000)->Arg(100000);

// A shipped scenario simulated and prepared as the pipeline does.
fit::PreparedData prepared(const std::string& scenario) {
  const sim::Scenario sc = sim::load_scenario(std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/" + scenario);
  const sim::SimulationResult r =
      sim::Simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(sc.gyro_file)).run();
  fit::Measurement m;
  m.file = scenario;
  m.time_s = r.time_s;
  m.temp_c = r.temp_c;
  m.gyro_dph = r.gyro_dph;
  return fit::prepare_data(m, {});
}

const fit::LinearProblem& cycle_problem() {
  static const fit::LinearProblem problem = [] {
    const fit::PreparedData d = prepared("cycle.toml");
    const auto terms = fit::parse_formula("T + T^2 + dT");
    const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(d.series.gyro_dph.data(),
                                                                static_cast<Eigen::Index>(d.series.size()));
    return fit::LinearProblem(fit::design_matrix(d.derived, terms, fit::default_parameters(terms)), y,
                              {"T", "T^2", "dT"});
  }();
  return problem;
}

const fit::PreparedData& random_72h() {
  static const fit::PreparedData data = prepared("random.toml");
  return data;
}

void BM_FitIntervals(benchmark::State& state, const std::string& method) {
  const fit::PreparedData& data = random_72h();
  const auto terms = fit::parse_formula("T + T^2 + dT");
  fit::EngineSettings settings;
  settings.options["intervals"] = method;
  for (auto _ : state)
    benchmark::DoNotOptimize(fit::fit_model(data, terms, fit::find_engine("ols"), settings));
  state.counters["windows"] = static_cast<double>(data.series.size());
}

void BM_IdentifyNoise(benchmark::State& state) {
  const fit::PreparedData& data = random_72h();
  const auto terms = fit::parse_formula("T + T^2 + dT");
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(),
                                                              static_cast<Eigen::Index>(data.series.size()));
  const fit::LinearProblem problem(fit::design_matrix(data.derived, terms, fit::default_parameters(terms)), y,
                                   {"T", "T^2", "dT"});
  for (auto _ : state) benchmark::DoNotOptimize(fit::identify_record_noise(data, problem));
}

// `compensate --causal` sample by sample on the first N hours of the 72 h
// random profile (1 Hz) with T + T^2 + dT + lag: each closed window reads the
// latest three and carries the lag, so the rate (samples/s) does not fall
// with the length (it did, O(n²), while every window re-derived the history).
void BM_CausalCompensate(benchmark::State& state) {
  static const sim::SimulationResult r = [] {
    const sim::Scenario sc = sim::load_scenario(std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/random.toml");
    return sim::Simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(sc.gyro_file)).run();
  }();
  const std::size_t n = std::min(r.time_s.size(), static_cast<std::size_t>(state.range(0)) * 3600);
  fit::SavedFit fit;
  fit.terms = fit::parse_formula("T + T^2 + dT + lag");
  fit.parameters = fit::default_parameters(fit.terms);
  fit.coefficients = {-7.0, {-3e-4, 1e-6, 1.8, 2e-4}};
  fit.pipeline.derivative = fit::DerivativeMode::causal;
  fit::CausalSettings settings;
  settings.sample_interval_s = 1.0;
  for (auto _ : state) {
    fit::CausalCompensator compensator(fit, settings);
    double sum = 0.0;
    for (std::size_t k = 0; k < n; ++k)
      sum += compensator.update(r.time_s[k], r.temp_c[k], 0.0, r.gyro_dph[k], {}, nullptr);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["samples/s"] =
      benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_CausalCompensate)->Arg(6)->Arg(24)->Arg(72)->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(BM_FitIntervals, model, std::string("model"))->Unit(benchmark::kMillisecond);
// The parametric bootstrap, 1000 draws per structure (aim: ≤ 1 s on 72 h).
BENCHMARK_CAPTURE(BM_FitIntervals, bootstrap, std::string("bootstrap"))->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyNoise)->Unit(benchmark::kMillisecond);

// `allan` on 2²⁰ samples (12 days at 1 s) of white plus flicker-like noise:
// the curve at octave τ, the series' noise model and the coefficients (aim ≤ 0.5 s).
void BM_AllanSeries(benchmark::State& state) {
  const std::size_t n = std::size_t{1} << 20;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> t(n), y(n);
  double slow = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = static_cast<double>(i);
    slow = 0.999 * slow + 0.002 * normal(rng);
    y[i] = 0.03 * normal(rng) + slow;
  }
  for (auto _ : state) benchmark::DoNotOptimize(studies::allan_series(t, y, {}, "raw"));
}
BENCHMARK(BM_AllanSeries)->Unit(benchmark::kMillisecond);

void BM_EngineToTarget(benchmark::State& state, const std::string& name) {
  const fit::LinearProblem& problem = cycle_problem();
  const double optimum = problem.objective(fit::least_squares_optimum(problem));
  const fit::EngineInfo& info = fit::find_engine(name);
  std::vector<double> evaluations;
  int reached = 0;
  for (auto _ : state) {
    evaluations.clear();
    reached = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
      fit::EngineSettings s;
      s.seed = seed;
      s.max_evaluations = info.stochastic ? 200000 : 0;
      s.target_objective = optimum * (1.0 + 1e-6);
      const fit::FitResult r = info.make(s)->fit(problem);
      const bool ok = r.objective <= optimum * (1.0 + 1e-6);
      reached += ok;
      evaluations.push_back(static_cast<double>(ok ? r.evaluations : s.max_evaluations));
    }
  }
  std::sort(evaluations.begin(), evaluations.end());
  state.counters["evals_median"] = 0.5 * (evaluations[4] + evaluations[5]);
  state.counters["reached_of_10"] = reached;
}

BENCHMARK_CAPTURE(BM_EngineToTarget, ols, std::string("ols"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EngineToTarget, afsa, std::string("afsa"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EngineToTarget, iafsa, std::string("iafsa"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EngineToTarget, pso, std::string("pso"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EngineToTarget, de, std::string("de"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EngineToTarget, cmaes, std::string("cmaes"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EngineToTarget, abc, std::string("abc"))->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
