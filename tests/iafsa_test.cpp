// Tests for fit/engines/iafsa.h. The known answers come from an Eigen least-squares
// solution of the same data (tests/lagged_cycle_problem.h), never from the engine itself: the
// paper's bias model on a synthetic −40..60 °C cycle (3 terms), the same
// without noise (the coefficients themselves must come back), and a 6-term
// model. Then the engine contract: same seed, same run; bad options named;
// defaults valid; target, budget and observer stops; eq. (5).

#include "studies/simulated.h"
#include "fit/engines/iafsa.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "fit/engines/engine.h"
#include "fit/model/linear_problem.h"
#include "sim/util/input_error.h"
#include "cli_runner.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "lagged_cycle_problem.h"
#include "sim/config_loader.h"
#include "sim/simulator.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing::lagged_cycle;

FitResult run(const LinearProblem& problem, EngineSettings settings,
              FitObserver* observer = nullptr) {
  return find_engine("iafsa").make(settings)->fit(problem, observer);
}

TEST(Iafsa, ReachesTheLeastSquaresOptimumOnThePaperCycleAtDefaults) {
  const DefaultRuns d = runs_at_defaults("iafsa");
  for (const FitResult& r : d.runs) {
    expect_near_optimum(d, r, 1e-6);
    EXPECT_LE(r.evaluations, 20000);
    EXPECT_EQ(r.termination, Termination::max_iterations);
    EXPECT_EQ(r.iterations, 700);
  }
}

TEST(Iafsa, RecoversTheCoefficientsOfNoiseFreeData) {
  // Worst relative error over 20 seeds 4e-6; the test allows 5e-5.
  expect_recovers_noise_free("iafsa", 5e-5, 1e-7);
}

TEST(Iafsa, ScalesToASixTermModelWithMoreFishAndASlowerSchedule) {
  // Six correlated terms (condition number ≈ 400): the range must shrink more
  // slowly (it collapses after ≈ 3·√G_max iterations), so G_max = 20000 and
  // 20 fish; they reach 1e-6 in a median of 19000 evaluations (at worst 23000
  // of 20 seeds) and the test gives them 40000. At 8 fish and G_max = 700 the
  // range collapses too early and σ stays well above the optimum.
  const auto [problem, optimum] = six_term_problem();
  ASSERT_GT(problem.condition_number(), 100.0);
  EngineSettings settings;
  settings.max_evaluations = 40000;
  settings.options = {{"fish", "20"}, {"max_iterations", "20000"}};
  const FitResult r = run(problem, settings);
  EXPECT_LE(sigma_at(problem, r), optimum * (1.0 + 1e-6));
  EXPECT_LE(r.evaluations, 40000);
}

TEST(Iafsa, AutoSizesTheSwarmAndTheScheduleByTheNumberOfTerms) {
  EXPECT_EQ(IafsaEngine::auto_fish(1), 8);
  EXPECT_EQ(IafsaEngine::auto_fish(3), 8);
  EXPECT_EQ(IafsaEngine::auto_fish(6), 20);
  EXPECT_EQ(IafsaEngine::auto_iterations(3), 700);
  EXPECT_EQ(IafsaEngine::auto_iterations(4), 1750);
  EXPECT_EQ(IafsaEngine::auto_iterations(6), 10937);
  EXPECT_EQ(IafsaEngine::auto_iterations(40), 100000000);  // capped

  // This problem was not used to choose the rule (fit/engines/iafsa.h): at the
  // default options and budget every seed reaches the target on the six
  // correlated terms, where the fixed 8 fish and G_max = 700 fall short.
  const Cycle c = cycle_design(true);
  const Eigen::VectorXd y = bias_dph(c.design, kSixTerm, 0.002);
  const LinearProblem problem = make_problem(c, y);
  const double optimum = least_squares_sigma(c.design, y);
  int fixed_short = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    EngineSettings settings;  // default budget (20000), auto fish and G_max
    settings.seed = seed;
    const FitResult r = run(problem, settings);
    EXPECT_LE(sigma_at(problem, r), optimum * (1.0 + 1e-6)) << "seed " << seed;
    EXPECT_EQ(r.detail.fish, 20);
    EXPECT_NE(run_text(r).find("20 fish"), std::string::npos) << run_text(r);
    settings.options = {{"fish", "8"}, {"max_iterations", "700"}};
    if (sigma_at(problem, run(problem, settings)) > optimum * (1.0 + 1e-6)) ++fixed_short;
  }
  EXPECT_GE(fixed_short, 3);
}

// The option strings are checked by the contract suite
// (engine_contract_test.cpp); the aggregate built in code is checked by the
// same table, and the stopping rules too.
TEST(Iafsa, ValidateChecksTheAggregate) {
  expect_aggregate_checked<IafsaEngine>({.fish = 1}, "iafsa option fish=1: must be a whole number from 2");
}

TEST(Iafsa, ShrinksVisualAndStepByEquationFive) {
  const Cycle c = cycle_design(false);
  const LinearProblem problem = make_problem(c, bias_dph(c.design, kPaper, 0.002));
  const int g_max = 10;
  const double visual = 0.4, step = 0.3, visual_min = 1e-3, step_min = 2e-3;
  for (const std::string schedule : {"initial", "compound"}) {
    EngineSettings settings;
    settings.options = {{"max_iterations", std::to_string(g_max)},
                        {"visual", "0.4"},
                        {"step", "0.3"},
                        {"visual_min", "1e-3"},
                        {"step_min", "2e-3"},
                        {"schedule", schedule}};
    // Eq. (5) after G_max iterations, α = exp(−3G/G_max).
    double v = visual, s = step;
    for (int g = 1; g <= g_max; ++g) {
      const double alpha = std::exp(-3.0 * g / g_max);
      v = (schedule == "compound" ? v : visual) * alpha + visual_min;
      s = (schedule == "compound" ? s : step) * alpha + step_min;
    }
    const FitResult r = run(problem, settings);
    EXPECT_EQ(r.termination, Termination::max_iterations);
    EXPECT_NEAR(r.detail.visual, v, 1e-12 * v) << "schedule " << schedule;
    EXPECT_NEAR(r.detail.step, s, 1e-12 * s) << "schedule " << schedule;
    EXPECT_NE(run_text(r).find(fmt::format("Visual {:.3g}, Step {:.3g}", v, s)), std::string::npos)
        << "schedule " << schedule << ": " << run_text(r);
  }
}

// The realistic check: the shipped cycle with the default noise; the
// paper's model by the pipeline; iafsa at its default budget and a fixed seed
// within 1e-6 relative of the least-squares σ.
TEST(Iafsa, MatchesLeastSquaresOnTheSimulatedCycle) {
  const sim::Scenario sc = sim::load_scenario(testing::source_path("scenarios/cycle.toml"));
  const sim::Simulator simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(sc.gyro_file));
  const sim::SimulationResult run = simulator.run();
  const Measurement m = studies::measurement_of(run, "cycle");
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
