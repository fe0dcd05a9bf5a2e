// The contract every registered engine keeps (docs/architecture.md, "House rules"), one suite
// run over the whole registry: a new engine is checked by registering it.
//
//  * known answer: noise-free data give σ → 0 (ols: the coefficients to
//    1e-9); with noise every engine reaches the exact least-squares σ and
//    none goes below it;
//  * the same seed gives the same run, another seed another one;
//  * the budget is never exceeded, the target stops the run, an observer
//    can stop it;
//  * every option of the engine's table is refused outside its rule (naming
//    the engine, KEY=VALUE and the rule), unknown keys and bad stopping rules
//    too;
//  * the listed defaults obey their rules and are the defaults used.
//
// Algorithm-specific behaviour stays in each engine's own test file.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fit/engines/engine.h"
#include "fit/engines/ols.h"
#include "fit_test_data.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

const LinearProblem& noisy_problem() {
  static const LinearProblem p = paper_problem(0.002, 0.8, 9);
  return p;
}

// A budget that lets every search engine converge on the 3-term problems here.
EngineSettings generous(const EngineInfo& info, std::uint64_t seed) {
  EngineSettings s;
  s.seed = seed;
  s.max_evaluations = info.stochastic ? 60000 : 0;
  return s;
}

class EngineContract : public ::testing::TestWithParam<std::string> {
 protected:
  const EngineInfo& info() const { return find_engine(GetParam()); }
  FitResult run(const EngineSettings& s, const LinearProblem& p, FitObserver* o = nullptr) const {
    return info().make(s)->fit(p, o);
  }
};

TEST_P(EngineContract, NoiseFreeDataGiveTheTruth) {
  const LinearProblem problem = paper_problem(0.0);
  const FitResult r = run(generous(info(), 3), problem);
  // All but 1e-8 of the variance explained.
  EXPECT_LE(r.objective, 1e-4 * problem.sigma_y()) << r.brief_report();
  if (!info().stochastic) {
    const Coefficients c = problem.physical(r.z);
    EXPECT_NEAR(c.b[0] / kB1, 1.0, 1e-9);
    EXPECT_NEAR(c.b[1] / kB2, 1.0, 1e-9);
    EXPECT_NEAR(c.b[2] / kB3, 1.0, 1e-9);
  }
}

TEST_P(EngineContract, NoisyDataReachTheLeastSquaresSigmaAndNeverBeatIt) {
  const double optimum = noisy_problem().objective(least_squares_optimum(noisy_problem()));
  const FitResult r = run(generous(info(), 5), noisy_problem());
  EXPECT_LE(r.objective, optimum * (1.0 + 1e-4)) << r.brief_report();
  EXPECT_GE(r.objective, optimum * (1.0 - 1e-12));
  EXPECT_FALSE(r.history.empty());
  EXPECT_EQ(r.engine, GetParam());
}

TEST_P(EngineContract, SameSeedSameRunOtherSeedOtherRun) {
  EngineSettings s;
  s.seed = 42;
  s.max_evaluations = info().stochastic ? 3000 : 0;
  const FitResult a = run(s, noisy_problem());
  const FitResult b = run(s, noisy_problem());
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.evaluations, b.evaluations);
  ASSERT_EQ(a.history.size(), b.history.size());
  for (std::size_t k = 0; k < a.history.size(); ++k) {
    EXPECT_EQ(a.history[k].evaluations, b.history[k].evaluations);
    EXPECT_EQ(a.history[k].best_objective, b.history[k].best_objective);
  }
  if (info().stochastic) {
    s.seed = 43;
    EXPECT_NE(run(s, noisy_problem()).z, a.z);
    EXPECT_LE(a.evaluations, 3000);
  }
}

TEST_P(EngineContract, BudgetTargetAndObserverStopTheRun) {
  if (!info().stochastic) GTEST_SKIP() << "a closed form: no budget, target or iterations";
  for (const long budget : {1L, 7L, 21L, 250L}) {
    EngineSettings s;
    s.seed = 5;
    s.max_evaluations = budget;
    const FitResult r = run(s, noisy_problem());
    EXPECT_EQ(r.evaluations, budget) << r.brief_report();  // spent to the last evaluation
    EXPECT_EQ(r.termination, Termination::budget_exhausted) << "budget " << budget;
    for (const HistoryPoint& h : r.history) EXPECT_LE(h.evaluations, budget);
  }
  EngineSettings s = generous(info(), 11);
  const double optimum = noisy_problem().objective(least_squares_optimum(noisy_problem()));
  s.target_objective = optimum * 1.01;
  const FitResult hit = run(s, noisy_problem());
  EXPECT_EQ(hit.termination, Termination::target_reached) << hit.brief_report();
  EXPECT_LE(hit.objective, s.target_objective);
  ASSERT_FALSE(hit.history.empty());
  EXPECT_EQ(hit.history.back().evaluations, hit.evaluations);

  // The observer hears every iteration in order, with growing counts and a
  // best σ that never rises, and stops the run when it says so.
  struct StopAtThree final : FitObserver {
    long calls = 0, last_evaluations = 0;
    double last_best = std::numeric_limits<double>::infinity();
    bool on_iteration(long iteration, long evaluations, double best_objective) override {
      EXPECT_EQ(iteration, ++calls);
      EXPECT_GT(evaluations, last_evaluations);
      EXPECT_LE(best_objective, last_best);
      last_evaluations = evaluations;
      last_best = best_objective;
      return calls < 3;
    }
  } observer;
  const FitResult stopped = run(generous(info(), 2), noisy_problem(), &observer);
  EXPECT_EQ(stopped.termination, Termination::stopped) << stopped.brief_report();
  EXPECT_EQ(stopped.iterations, 3);
  EXPECT_EQ(stopped.evaluations, observer.last_evaluations);
}

// A rejected option names the engine, KEY=VALUE and the rule.
void expect_rejected(const EngineInfo& info, const std::string& key, const std::string& value,
                     const std::string& rule) {
  SCOPED_TRACE(info.name + " " + key + "=" + value);
  EngineSettings s;
  s.options = {{key, value}};
  try {
    info.make(s);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(info.name), std::string::npos) << message;
    EXPECT_NE(message.find(key + "=" + value), std::string::npos) << message;
    EXPECT_NE(message.find(rule), std::string::npos) << message;
  }
}

std::string number_text(double v) { return fmt::format("{}", v); }

TEST_P(EngineContract, EveryOptionIsRefusedOutsideItsRule) {
  const EngineInfo& e = info();
  for (const OptionInfo& o : e.options) {
    ASSERT_TRUE(o.rule) << o.keyword << ": an engine's option has a rule";
    const OptionRule& r = *o.rule;
    const std::string rule = "must be " + r.text();
    if (r.kind == OptionRule::Kind::choice) {
      expect_rejected(e, o.keyword, "no-such-choice", rule);
      continue;
    }
    expect_rejected(e, o.keyword, "abc", "expected a number");
    // Just below the range (at it, when the bound is open), skipping a value
    // the rule allows besides the range (0: automatic).
    const double below = r.lower_open ? r.lower : r.lower - (r.kind == OptionRule::Kind::integer ? 1.0 : 0.5);
    if (!r.allows(below)) expect_rejected(e, o.keyword, number_text(below), rule);
    if (r.upper < std::numeric_limits<double>::max()) expect_rejected(e, o.keyword, number_text(r.upper + 1.0), rule);
    if (r.kind == OptionRule::Kind::integer) expect_rejected(e, o.keyword, number_text(r.lower + 0.5), rule);
    // A value with a word (auto) is written as the word, not as its number.
    if (r.extra && !r.extra_word.empty()) expect_rejected(e, o.keyword, number_text(*r.extra), rule);
  }
  EngineSettings unknown;
  unknown.options = {{"no_such_option", "1"}};
  try {
    e.make(unknown);
    ADD_FAILURE() << "an unknown key was accepted";
  } catch (const InputError& x) {
    EXPECT_NE(std::string(x.what()).find(e.name + " has no option 'no_such_option'"), std::string::npos)
        << x.what();
  }
  if (e.stochastic) {
    EngineSettings negative_budget;
    negative_budget.max_evaluations = -5;
    EXPECT_THROW(e.make(negative_budget), InputError);
    EngineSettings negative_target;
    negative_target.target_objective = -1.0;
    EXPECT_THROW(e.make(negative_target), InputError);
  }
}

TEST_P(EngineContract, ListedDefaultsObeyTheirRulesAndAreTheDefaultsUsed) {
  const EngineInfo& e = info();
  EXPECT_FALSE(e.description.empty());
  EXPECT_NO_THROW(e.make(EngineSettings{}));
  EngineSettings listed;
  listed.seed = 1;
  listed.max_evaluations = e.stochastic ? 500 : 0;
  for (const OptionInfo& o : e.options) {
    SCOPED_TRACE(e.name + " " + o.keyword + " = " + o.default_value);
    EXPECT_FALSE(o.help.empty());
    EXPECT_EQ(option_line(o).rfind(o.default_value + ": ", 0), 0u);
    listed.options[o.keyword] = o.default_value;
  }
  EngineSettings implicit = listed;
  implicit.options.clear();
  const FitResult a = run(listed, noisy_problem());
  const FitResult b = run(implicit, noisy_problem());
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(a.evaluations, b.evaluations);
  if (e.stochastic) {
    EXPECT_GT(e.default_evaluations, 0);
  }
}

std::vector<std::string> registered() {
  std::vector<std::string> names;
  for (const EngineInfo& e : engine_registry()) names.push_back(e.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Registry, EngineContract, ::testing::ValuesIn(registered()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

TEST(EngineRegistry, HoldsTheIssuesEnginesAndNamesTheKnownOnes) {
  EXPECT_EQ(registered(), (std::vector<std::string>{"ols", "gls", "stepwise", "afsa", "iafsa", "pso", "de",
                                                    "cmaes", "abc"}));
  try {
    find_engine("ga");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown engine 'ga' (known engines: ols, gls, stepwise"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace gyrotherm::fit
