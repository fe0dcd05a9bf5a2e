// Every registered engine against the exact least-squares optimum, on the
// same problems (STYLE.md rule 10, for the registry as a whole).

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "fit/engines/engine.h"
#include "fit/model/formula.h"
#include "fit/engines/ols.h"
#include "fit/pipeline.h"
#include "fit_test_data.h"
#include "sim/config_loader.h"
#include "sim/output.h"
#include "sim/util/input_error.h"
#include "sim/simulator.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

TEST(Engines, RegistryHoldsTheIssuesEngines) {
  std::vector<std::string> names;
  for (const EngineInfo& e : engine_registry()) names.push_back(e.name);
  EXPECT_EQ(names, (std::vector<std::string>{"ols", "stepwise", "afsa", "iafsa", "pso", "de",
                                             "cmaes", "abc"}));
  for (const EngineInfo& e : engine_registry()) EXPECT_NO_THROW(e.make(EngineSettings{})) << e.name;
}

TEST(Engines, UnknownEngineListsTheKnownOnes) {
  try {
    find_engine("ga");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown engine 'ga' (known engines: ols, stepwise"),
              std::string::npos);
  }
}

// Noise-free: the optimum is σ = 0 and the truth is recoverable. ols must hit
// the coefficients to 1e-9; the searches must bring σ to 1e-4 of the raw
// std(y), i.e. explain all but 1e-8 of its variance.
TEST(Engines, NoiseFreeDataEveryEngineFindsTheOptimum) {
  const LinearProblem problem = paper_problem(0.0);
  for (const EngineInfo& info : engine_registry()) {
    EngineSettings s;
    s.seed = 3;
    s.max_evaluations = info.stochastic ? 60000 : 0;
    const FitResult r = info.make(s)->fit(problem);
    EXPECT_LE(r.objective, 1e-4 * problem.sigma_y()) << info.name << ": " << r.brief_report();
    if (info.name == "ols") {
      const Coefficients c = problem.physical(r.z);
      EXPECT_NEAR(c.b[0] / kB1, 1.0, 1e-9);
      EXPECT_NEAR(c.b[1] / kB2, 1.0, 1e-9);
      EXPECT_NEAR(c.b[2] / kB3, 1.0, 1e-9);
    }
  }
}

// With noise: every engine within 1e-4 of the optimal σ at a generous budget.
TEST(Engines, NoisyDataEveryEngineReachesTheOptimalSigma) {
  const LinearProblem problem = paper_problem(0.002, 0.8, 9);
  const double optimum = problem.objective(least_squares_optimum(problem));
  for (const EngineInfo& info : engine_registry()) {
    EngineSettings s;
    s.seed = 5;
    s.max_evaluations = info.stochastic ? 60000 : 0;
    const FitResult r = info.make(s)->fit(problem);
    EXPECT_LE(r.objective, optimum * (1.0 + 1e-4)) << info.name << ": " << r.brief_report();
    EXPECT_GE(r.objective, optimum * (1.0 - 1e-12)) << info.name;  // nothing beats least squares
    EXPECT_FALSE(r.history.empty()) << info.name;
  }
}

TEST(Engines, StochasticEnginesRepeatWithTheSeedAndDifferWithout) {
  const LinearProblem problem = paper_problem(0.002, 0.5, 2);
  for (const EngineInfo& info : engine_registry()) {
    if (!info.stochastic) continue;
    EngineSettings s;
    s.seed = 42;
    s.max_evaluations = 3000;
    const FitResult a = info.make(s)->fit(problem);
    const FitResult b = info.make(s)->fit(problem);
    s.seed = 43;
    const FitResult c = info.make(s)->fit(problem);
    EXPECT_EQ(a.z, b.z) << info.name;
    EXPECT_EQ(a.evaluations, b.evaluations) << info.name;
    ASSERT_EQ(a.history.size(), b.history.size()) << info.name;
    for (std::size_t k = 0; k < a.history.size(); ++k) {
      EXPECT_EQ(a.history[k].evaluations, b.history[k].evaluations) << info.name;
      EXPECT_EQ(a.history[k].best_objective, b.history[k].best_objective) << info.name;
    }
    EXPECT_NE(a.z, c.z) << info.name;
    EXPECT_LE(a.evaluations, 3000) << info.name;
  }
}

// The issue's realistic check: the shipped cycle with the default noise; the
// paper's model by the pipeline; iafsa at its default budget and a fixed seed
// within 1e-6 relative of the least-squares σ.
TEST(Engines, IafsaMatchesLeastSquaresOnTheSimulatedCycle) {
  const sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  const sim::Simulator simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(sc.gyro_file));
  const sim::SimulationResult run = simulator.run();
  Measurement m;
  m.file = "cycle";
  m.time_s = run.time_s;
  m.temp_c = run.temp_c;
  m.gyro_dph = run.gyro_dph;
  m.temp2_c = run.temp2_c;
  const PreparedData data = prepare_data(m, PipelineOptions{});
  const auto terms = parse_formula("T + T^2 + dT");
  EngineSettings s;
  s.seed = 1;
  const ModelFit ols = fit_model(data, terms, find_engine("ols"), s);
  const ModelFit iafsa = fit_model(data, terms, find_engine("iafsa"), s);
  EXPECT_LE(iafsa.instability_after_dph / ols.instability_after_dph - 1.0, 1e-6)
      << iafsa.engine.brief_report();
  EXPECT_GT(ols.ratio(), 2.0);
}

}  // namespace
}  // namespace gyrotherm::fit
