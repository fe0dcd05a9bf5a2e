// Tests for fit/engines/afsa.h. The known answers come from an Eigen least-squares
// solution of the same data (tests/lagged_cycle_problem.h), never from the engine itself: the
// paper's bias model on a synthetic −40..60 °C cycle (3 terms), the same
// without noise, and a 6-term model. Basic AFSA moves with a fixed Step, so it
// polishes slowly: its tolerances are looser than IAFSA's (fit/iafsa_test.cpp)
// and stated at each test. Then the engine contract: same seed, same run; bad
// options named; defaults valid; target, budget and observer stops.

#include "fit/engines/afsa.h"

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
#include "lagged_cycle_problem.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing::lagged_cycle;

FitResult run(const LinearProblem& problem, EngineSettings settings,
              FitObserver* observer = nullptr) {
  return find_engine("afsa").make(settings)->fit(problem, observer);
}

TEST(Afsa, ComesCloseToTheLeastSquaresOptimumOnThePaperCycleAtDefaults) {
  // At its default budget (20000 evaluations) AFSA lands within ~1e-5 of the
  // optimum σ (worst of 20 seeds 1.4e-5); the test allows 1e-3.
  const DefaultRuns d = runs_at_defaults("afsa");
  for (const FitResult& r : d.runs) {
    expect_near_optimum(d, r, 1e-3);
    EXPECT_EQ(r.evaluations, 20000);
    EXPECT_EQ(r.termination, Termination::budget_exhausted);
  }
}

TEST(Afsa, RecoversTheCoefficientsOfNoiseFreeDataToAFewPercent) {
  // The fixed Step limits how finely the swarm settles: the coefficients come
  // back within 1 % (worst of 20 seeds 0.8 %); the test allows 5 %.
  expect_recovers_noise_free("afsa", 5e-2, 1e-4);
}

TEST(Afsa, ScalesToASixTermModelWithMoreFishAndEvaluations) {
  // Six correlated terms (condition number ≈ 400): 40 fish and 100000
  // evaluations bring σ within 3e-3 of the optimum (worst of 20 seeds); the
  // test allows 1e-2.
  const auto [problem, optimum] = six_term_problem();
  ASSERT_GT(problem.condition_number(), 100.0);
  EngineSettings settings;
  settings.max_evaluations = 100000;
  settings.options = {{"fish", "40"}};
  const FitResult r = run(problem, settings);
  EXPECT_LE(sigma_at(problem, r), optimum * (1.0 + 1e-2));
  EXPECT_EQ(r.evaluations, 100000);
}

// The option strings are checked by the contract suite
// (engine_contract_test.cpp); the aggregate built in code is checked by the
// same table, and the stopping rules too.
TEST(Afsa, ValidateChecksTheAggregate) {
  expect_aggregate_checked<AfsaEngine>({.step = 0.0}, "afsa option step=0: must be > 0");
}

}  // namespace
}  // namespace gyrotherm::fit
