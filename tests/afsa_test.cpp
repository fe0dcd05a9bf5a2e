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
  const Cycle c = cycle_design(false);
  const LinearProblem problem = make_problem(c, bias_dph(c.design, kPaper, 0.0));
  const FitResult r = run(problem, EngineSettings{});
  const Coefficients fitted = problem.physical(r.z);
  for (std::size_t j = 0; j < kPaper.size(); ++j)
    EXPECT_NEAR(fitted.b[j], kPaper[j], 5e-2 * std::abs(kPaper[j])) << c.names[j];
  EXPECT_NEAR(fitted.intercept, kIntercept, 1e-4 * std::abs(kIntercept));
}

TEST(Afsa, ScalesToASixTermModelWithMoreFishAndEvaluations) {
  // Six correlated terms (condition number ≈ 400): 40 fish and 100000
  // evaluations bring σ within 3e-3 of the optimum (worst of 20 seeds); the
  // test allows 1e-2.
  const Cycle c = cycle_design(true);
  const Eigen::VectorXd y = bias_dph(c.design, kSixTerm, 0.002);
  const LinearProblem problem = make_problem(c, y);
  ASSERT_GT(problem.condition_number(), 100.0);
  const double optimum = least_squares_sigma(c.design, y);
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
  try {
    AfsaEngine{AfsaEngine::Options{.step = 0.0}};
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("afsa option step=0: must be > 0"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(AfsaEngine::Options{}.validate());
  try {
    AfsaEngine{AfsaEngine::Options{.max_evaluations = -5}};
    ADD_FAILURE() << "max_evaluations = -5 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_evaluations=-5: must be at least 1"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(AfsaEngine{AfsaEngine::Options{.target_objective = -1.0}}, InputError);
}

}  // namespace
}  // namespace gyrotherm::fit
