// The pagmo engines (pso, de, cmaes, abc) against a synthetic RLG thermal
// test whose optimum is known exactly.
//
// Temperature follows a smooth cycle between −40 and 60 °C,
//     T(t) = 10 − 50 cos(2π t / P),   two periods over l = 300 points (100 s means),
// and the gyro output is a known compensation model plus small noise,
//     y = 0.3 + 0.02 T + 3e-4 T² + 0.5 dT/dt [°C/min] + ε,   ε ~ N(0, 0.01²) °/h.
// The best σ any engine can reach is that of the ordinary least-squares
// residual with an intercept, σ* = sqrt(RSS / (l − 1)), computed here with
// Eigen's QR, independently of LinearProblem's Gram form.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "fit/engines/engine.h"
#include "fit/model/linear_problem.h"
#include "fit/engines/pagmo_engines.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

struct PagmoSynthetic {
  LinearProblem problem;
  double optimum;  // σ*
};

PagmoSynthetic make_synthetic() {
  constexpr int l = 300;
  constexpr double dt_s = 100.0;
  constexpr double period_s = l * dt_s / 2.0;
  constexpr double w = 2.0 * std::numbers::pi / period_s;
  std::mt19937_64 rng(20240611);
  std::normal_distribution<double> noise(0.0, 0.01);
  Eigen::MatrixXd x(l, 3);
  Eigen::VectorXd y(l);
  for (int p = 0; p < l; ++p) {
    const double t = (p + 0.5) * dt_s;
    const double temp_c = 10.0 - 50.0 * std::cos(w * t);
    const double rate_c_per_min = 50.0 * w * std::sin(w * t) * 60.0;
    x(p, 0) = temp_c;
    x(p, 1) = temp_c * temp_c;
    x(p, 2) = rate_c_per_min;
    y[p] = 0.3 + 0.02 * temp_c + 3e-4 * temp_c * temp_c + 0.5 * rate_c_per_min + noise(rng);
  }
  Eigen::MatrixXd a(l, 4);
  a << Eigen::VectorXd::Ones(l), x;
  const Eigen::VectorXd b = a.colPivHouseholderQr().solve(y);
  const double rss = (y - a * b).squaredNorm();
  const double optimum = std::sqrt(rss / (l - 1));
  return {LinearProblem(x, y, {"T", "T^2", "dT/dt"}), optimum};
}

const PagmoSynthetic& synthetic() {
  static const PagmoSynthetic s = make_synthetic();
  return s;
}

EngineSettings settings(std::uint64_t seed, long max_evaluations, double target_objective = 0.0,
                        std::map<std::string, std::string> options = {}) {
  EngineSettings s;
  s.seed = seed;
  s.max_evaluations = max_evaluations;
  s.target_objective = target_objective;
  s.options = std::move(options);
  return s;
}

FitResult run(const std::string& engine, const EngineSettings& s, FitObserver* observer = nullptr) {
  return find_engine(engine).make(s)->fit(synthetic().problem, observer);
}

class PagmoEngineTest : public ::testing::TestWithParam<std::string> {};

TEST(PagmoEngines, RegistersFourStochasticEngines) {
  const std::vector<EngineInfo> infos = pagmo_engine_infos();
  ASSERT_EQ(infos.size(), 4u);
  EXPECT_EQ(infos[0].name, "pso");
  EXPECT_EQ(infos[1].name, "de");
  EXPECT_EQ(infos[2].name, "cmaes");
  EXPECT_EQ(infos[3].name, "abc");
  for (const EngineInfo& info : infos) {
    EXPECT_TRUE(info.stochastic) << info.name;
    EXPECT_EQ(info.default_evaluations, kPagmoDefaultEvaluations) << info.name;
    EXPECT_FALSE(info.options.empty()) << info.name;
    EXPECT_TRUE(static_cast<bool>(info.make)) << info.name;
  }
}

// Known answer: the least-squares σ, to 1e-4 relative, at the default budget.
TEST_P(PagmoEngineTest, ReachesTheLeastSquaresOptimum) {
  const FitResult r = run(GetParam(), settings(3, 0));
  const double optimum = synthetic().optimum;
  EXPECT_LE(r.objective, optimum * (1.0 + 1e-4)) << r.brief_report();
  EXPECT_GE(r.objective, optimum * (1.0 - 1e-9)) << r.brief_report();
  EXPECT_EQ(r.engine, GetParam());
  EXPECT_LE(r.evaluations, kPagmoDefaultEvaluations);
  EXPECT_GT(r.iterations, 0);
  ASSERT_EQ(r.z.size(), 3u);
  for (double v : r.z) {
    EXPECT_GE(v, -1.0);
    EXPECT_LE(v, 1.0);
  }
  // The reported point is the reported σ, and it is the σ of the residuals.
  EXPECT_EQ(synthetic().problem.objective(r.z), r.objective);
  EXPECT_NEAR(synthetic().problem.sigma_two_pass(synthetic().problem.physical(r.z)), r.objective,
              1e-9 * r.objective);
  // The history improves strictly and ends at the result.
  ASSERT_FALSE(r.history.empty());
  for (std::size_t i = 1; i < r.history.size(); ++i) {
    EXPECT_GT(r.history[i].evaluations, r.history[i - 1].evaluations);
    EXPECT_LT(r.history[i].best_objective, r.history[i - 1].best_objective);
  }
  EXPECT_EQ(r.history.back().best_objective, r.objective);
  EXPECT_LE(r.history.back().evaluations, r.evaluations);
}

// The budget is exact: never exceeded, and spent to the last evaluation,
// including budgets that end inside a generation or inside the initial
// population (population 20; abc spends 40 per generation).
TEST_P(PagmoEngineTest, BudgetIsNeverExceeded) {
  for (const long budget : {1L, 13L, 20L, 21L, 59L, 1237L}) {
    const FitResult r = run(GetParam(), settings(5, budget, 0.0, {{"population", "20"}}));
    EXPECT_EQ(r.evaluations, budget) << "budget " << budget << ": " << r.brief_report();
    EXPECT_EQ(r.termination, Termination::budget_exhausted) << r.brief_report();
    const long per_generation = GetParam() == "abc" ? 40 : 20;
    EXPECT_EQ(r.iterations, budget > 20 ? (budget - 20) / per_generation : 0) << "budget " << budget;
  }
}

TEST_P(PagmoEngineTest, DefaultBudgetIsUsedWhenZero) {
  // No target: the run spends exactly the default budget unless the
  // population collapses first (de, cmaes: xtol).
  const FitResult r = run(GetParam(), settings(1, 0));
  EXPECT_LE(r.evaluations, kPagmoDefaultEvaluations);
  if (r.termination == Termination::budget_exhausted) {
    EXPECT_EQ(r.evaluations, kPagmoDefaultEvaluations);
  } else {
    EXPECT_EQ(r.termination, Termination::converged) << r.brief_report();
  }
}

// The run stops at the very evaluation that reaches the target.
TEST_P(PagmoEngineTest, StopsAtTheTarget) {
  const double target = synthetic().optimum * 1.01;
  const FitResult r = run(GetParam(), settings(11, 0, target));
  EXPECT_EQ(r.termination, Termination::target_reached) << r.brief_report();
  EXPECT_LE(r.objective, target);
  ASSERT_FALSE(r.history.empty());
  EXPECT_EQ(r.history.back().evaluations, r.evaluations);
  EXPECT_LT(r.evaluations, kPagmoDefaultEvaluations);

  // A target any point meets stops inside the initial population.
  const FitResult first = run(GetParam(), settings(11, 0, 10.0 * synthetic().problem.sigma_y()));
  EXPECT_EQ(first.termination, Termination::target_reached) << first.brief_report();
  EXPECT_EQ(first.evaluations, 1);
  EXPECT_EQ(first.iterations, 0);
}

// pso's ring needs 2 ≤ neighbours < population (11 with the automatic swarm
// of at least 12): a rule between two options, beyond the table's ranges.
TEST(PagmoEngines, PsoNeighboursMustFitTheSwarm) {
  for (const auto& [options, rule] :
       std::vector<std::pair<std::map<std::string, std::string>, std::string>>{
           {{{"neighbours", "12"}}, "neighbours=12: must be a whole number from 2 to 11"},
           {{{"population", "8"}, {"neighbours", "8"}}, "neighbours=8: must be a whole number from 2 to 7"}}) {
    try {
      find_engine("pso").make(settings(1, 0, 0.0, options));
      ADD_FAILURE() << rule;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("pso option " + rule), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(find_engine("pso").make(settings(1, 0, 0.0, {{"population", "8"}, {"neighbours", "7"}})));
}

INSTANTIATE_TEST_SUITE_P(Engines, PagmoEngineTest, ::testing::Values("pso", "de", "cmaes", "abc"),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param; });

}  // namespace
}  // namespace gyrotherm::fit
