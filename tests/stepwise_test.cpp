// stepwise: keeps the true terms, drops a term whose true coefficient is zero.

#include "fit/engines/stepwise.h"

#include <gtest/gtest.h>

#include "fit/engines/ols.h"
#include "fit_test_data.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

// The paper's three terms plus T³, whose true coefficient is 0; white noise,
// as stepwisefit's F-tests assume.
LinearProblem problem_with_spurious_term(std::uint64_t seed) {
  AveragedSeries s = synthetic_cycle(400);
  const DerivedSeries d = derive(s, DerivativeMode::central);
  const auto terms = parse_formula("T + T^2 + dT + T^3");
  const Eigen::MatrixXd x = design_matrix(d, terms, default_parameters(terms));
  boost::random::mt19937_64 rng(seed);
  boost::random::normal_distribution<double> normal(0.0, 0.002);
  Eigen::VectorXd y(x.rows());
  for (Eigen::Index p = 0; p < x.rows(); ++p)
    y[p] = kB0 + kB1 * x(p, 0) + kB2 * x(p, 1) + kB3 * x(p, 2) + normal(rng);
  return LinearProblem(x, y, {"T", "T^2", "dT", "T^3"});
}

TEST(Stepwise, KeepsTheTrueTermsAndDropsTheSpuriousOne) {
  int dropped = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const LinearProblem problem = problem_with_spurious_term(seed);
    const FitResult r = StepwiseEngine({}).fit(problem);
    ASSERT_EQ(r.inference.kept.size(), 4u);
    EXPECT_TRUE(r.inference.kept[0] && r.inference.kept[1] && r.inference.kept[2]) << run_text(r);
    dropped += !r.inference.kept[3];
    if (!r.inference.kept[3]) {
      EXPECT_EQ(r.z[3], 0.0);
    }
  }
  // A 5 % entry test keeps the null term in about 1 case in 20.
  EXPECT_GE(dropped, 16);
}

TEST(Stepwise, WithAllTermsKeptItIsTheLeastSquaresFit) {
  const LinearProblem problem = paper_problem(0.002, 0.0, 5);
  const FitResult r = StepwiseEngine({}).fit(problem);
  const std::vector<double> opt = least_squares_optimum(problem);
  for (std::size_t j = 0; j < 3; ++j) EXPECT_NEAR(r.z[j], opt[j], 1e-9);
}

// Each option's own range is in the contract suite; the rule between the two
// is stepwise's own.
TEST(Stepwise, RemovingMustNotBeEasierThanEntering) {
  EngineSettings s;
  s.options["p_enter"] = "0.2";
  s.options["p_remove"] = "0.1";
  try {
    stepwise_engine_info().make(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("p_remove=0.1 must be >= p_enter=0.2"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(StepwiseEngine(StepwiseOptions{.p_enter = 0.2, .p_remove = 0.1}), InputError);
  s.options["p_remove"] = "0.2";
  EXPECT_NO_THROW(stepwise_engine_info().make(s));
}

}  // namespace
}  // namespace gyrotherm::fit
