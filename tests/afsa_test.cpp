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
  const Cycle c = cycle_design(false);
  const Eigen::VectorXd y = bias_dph(c.design, kPaper, 0.002);
  const LinearProblem problem = make_problem(c, y);
  const double optimum = least_squares_sigma(c.design, y);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    EngineSettings settings;  // default budget, no target
    settings.seed = seed;
    const FitResult r = run(problem, settings);
    EXPECT_LE(r.objective, optimum * (1.0 + 1e-3)) << "seed " << seed;
    EXPECT_LE(sigma_at(problem, r), optimum * (1.0 + 1e-3)) << "seed " << seed;
    EXPECT_GE(sigma_at(problem, r), optimum * (1.0 - 1e-12)) << "seed " << seed;
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

TEST(Afsa, SameSeedGivesTheSameRunAndHistory) {
  const Cycle c = cycle_design(false);
  const LinearProblem problem = make_problem(c, bias_dph(c.design, kPaper, 0.002));
  EngineSettings settings;
  settings.seed = 7;
  settings.max_evaluations = 3000;
  const FitResult a = run(problem, settings);
  const FitResult b = run(problem, settings);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.objective, b.objective);
  EXPECT_EQ(a.evaluations, b.evaluations);
  EXPECT_EQ(a.iterations, b.iterations);
  ASSERT_EQ(a.history.size(), b.history.size());
  for (std::size_t k = 0; k < a.history.size(); ++k) {
    EXPECT_EQ(a.history[k].evaluations, b.history[k].evaluations);
    EXPECT_EQ(a.history[k].best_objective, b.history[k].best_objective);
  }
}

TEST(Afsa, DifferentSeedsGiveDifferentHistories) {
  const Cycle c = cycle_design(false);
  const LinearProblem problem = make_problem(c, bias_dph(c.design, kPaper, 0.002));
  EngineSettings settings;
  settings.max_evaluations = 3000;
  settings.seed = 1;
  const FitResult a = run(problem, settings);
  settings.seed = 2;
  const FitResult b = run(problem, settings);
  const auto same = [](const HistoryPoint& p, const HistoryPoint& q) {
    return p.evaluations == q.evaluations && p.best_objective == q.best_objective;
  };
  EXPECT_FALSE(a.history.size() == b.history.size() &&
               std::equal(a.history.begin(), a.history.end(), b.history.begin(), same));
  EXPECT_NE(a.z, b.z);
}

TEST(Afsa, RejectsBadOptionsNamingOptionValueAndRule) {
  // An unknown key is named with the keys the engine does know instead.
  struct Case {
    std::string key, value, rule;
  };
  const std::vector<Case> cases = {
      {"fish", "1", "whole number from 2"},
      {"fish", "ten", "expected a number"},
      {"max_iterations", "0", "whole number from 1"},
      {"visual", "0", "must be > 0"},
      {"visual", "1.5", "<= 1"},
      {"step", "-0.1", "must be > 0"},
      {"crowding", "0", "must be > 0"},
      {"crowding", "1.2", "<= 1"},
      {"try_number", "0", "whole number from 1"},
      {"visual_min", "0.1", "has no option 'visual_min'"},
  };
  for (const Case& k : cases) {
    EngineSettings settings;
    settings.options = {{k.key, k.value}};
    try {
      find_engine("afsa").make(settings);
      ADD_FAILURE() << k.key << "=" << k.value << " was accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("afsa"), std::string::npos) << message;
      EXPECT_NE(message.find(k.key), std::string::npos) << message;
      if (k.rule.find("has no option") == std::string::npos) {
        EXPECT_NE(message.find(k.key + "=" + k.value), std::string::npos) << message;
      }
      EXPECT_NE(message.find(k.rule), std::string::npos) << message;
    }
  }
  try {
    AfsaEngine{AfsaEngine::Options{.step = 0.0}};
    ADD_FAILURE() << "step = 0 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("step=0: must be > 0"), std::string::npos) << e.what();
  }
  EngineSettings negative_budget;
  negative_budget.max_evaluations = -5;
  try {
    find_engine("afsa").make(negative_budget);
    ADD_FAILURE() << "max_evaluations = -5 was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("max_evaluations=-5: must be at least 1"),
              std::string::npos)
        << e.what();
  }
  EngineSettings negative_target;
  negative_target.target_objective = -1.0;
  EXPECT_THROW(find_engine("afsa").make(negative_target), InputError);
}

TEST(Afsa, DefaultOptionsAreValidAndListedInTheRegistry) {
  EXPECT_NO_THROW(AfsaEngine::Options{}.validate());
  const EngineInfo& info = find_engine("afsa");
  EXPECT_TRUE(info.stochastic);
  EXPECT_EQ(info.default_evaluations, AfsaEngine::Options{}.max_evaluations);
  EXPECT_EQ(info.default_evaluations, 20000);
  // Every listed option, given back its listed default, is accepted and
  // leaves the engine at its defaults.
  EngineSettings settings;
  for (const auto& [name, text] : info.options)
    settings.options[name] = text.substr(0, text.find(':'));
  EXPECT_EQ(settings.options.size(), 6u);
  const std::unique_ptr<Engine> engine = info.make(settings);
  const auto* afsa = dynamic_cast<const AfsaEngine*>(engine.get());
  ASSERT_NE(afsa, nullptr);
  const AfsaEngine::Options d;
  const AfsaEngine::Options& o = afsa->options();
  EXPECT_EQ(o.fish, d.fish);
  EXPECT_EQ(o.max_iterations, d.max_iterations);
  EXPECT_EQ(o.visual, d.visual);
  EXPECT_EQ(o.step, d.step);
  EXPECT_EQ(o.crowding, d.crowding);
  EXPECT_EQ(o.try_number, d.try_number);
  EXPECT_EQ(o.max_evaluations, d.max_evaluations);
}

TEST(Afsa, StopsAtTheTarget) {
  const Cycle c = cycle_design(false);
  const Eigen::VectorXd y = bias_dph(c.design, kPaper, 0.002);
  const LinearProblem problem = make_problem(c, y);
  EngineSettings settings;
  settings.target_objective = least_squares_sigma(c.design, y) * (1.0 + 1e-2);
  const FitResult r = run(problem, settings);
  EXPECT_EQ(r.termination, Termination::target_reached);
  EXPECT_LE(r.objective, settings.target_objective);
  ASSERT_FALSE(r.history.empty());
  EXPECT_EQ(r.history.back().evaluations, r.evaluations);
  EXPECT_LT(r.evaluations, 20000);
}

TEST(Afsa, NeverExceedsTheEvaluationBudget) {
  const Cycle c = cycle_design(false);
  const LinearProblem problem = make_problem(c, bias_dph(c.design, kPaper, 0.002));
  for (const long budget : {1L, 7L, 20L, 21L, 250L, 1234L}) {
    EngineSettings settings;
    settings.max_evaluations = budget;
    const FitResult r = run(problem, settings);
    EXPECT_EQ(r.evaluations, budget);
    EXPECT_EQ(r.termination, Termination::budget_exhausted) << budget;
    for (const HistoryPoint& h : r.history) EXPECT_LE(h.evaluations, budget);
  }
}

class Recorder : public FitObserver {
 public:
  explicit Recorder(long stop_after) : stop_after_(stop_after) {}
  bool on_iteration(long iteration, long evaluations, double best_objective) override {
    iterations.push_back(iteration);
    evaluations_seen.push_back(evaluations);
    best.push_back(best_objective);
    return iteration < stop_after_;
  }
  std::vector<long> iterations, evaluations_seen;
  std::vector<double> best;

 private:
  long stop_after_;
};

TEST(Afsa, ObserverSeesEveryIterationAndCanStop) {
  const Cycle c = cycle_design(false);
  const LinearProblem problem = make_problem(c, bias_dph(c.design, kPaper, 0.002));

  Recorder stopper(5);
  const FitResult stopped = run(problem, EngineSettings{}, &stopper);
  EXPECT_EQ(stopped.termination, Termination::stopped);
  EXPECT_EQ(stopped.iterations, 5);
  EXPECT_EQ(stopper.iterations, (std::vector<long>{1, 2, 3, 4, 5}));
  EXPECT_EQ(stopper.evaluations_seen.back(), stopped.evaluations);

  EngineSettings settings;
  settings.options = {{"max_iterations", "30"}};
  Recorder watcher(1000);
  const FitResult r = run(problem, settings, &watcher);
  EXPECT_EQ(r.termination, Termination::max_iterations);
  EXPECT_EQ(r.iterations, 30);
  ASSERT_EQ(watcher.iterations.size(), 30u);
  for (std::size_t k = 1; k < watcher.iterations.size(); ++k) {
    EXPECT_EQ(watcher.iterations[k], watcher.iterations[k - 1] + 1);
    EXPECT_GT(watcher.evaluations_seen[k], watcher.evaluations_seen[k - 1]);
    EXPECT_LE(watcher.best[k], watcher.best[k - 1]);
  }
  EXPECT_EQ(watcher.best.back(), r.objective);
}

}  // namespace
}  // namespace gyrotherm::fit
