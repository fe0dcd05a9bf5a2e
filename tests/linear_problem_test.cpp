// The objective in the Gram form against the residuals themselves, the
// coordinate maps, the search box, and the checks on unfittable designs.

#include "fit/model/linear_problem.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "fit/engines/ols.h"
#include "fit_test_data.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using gyrotherm::testing::paper_problem;

TEST(LinearProblem, GramObjectiveAgreesWithTwoPassOnRealisticData) {
  // Realistic: the paper's magnitudes, noise 0.002 °/h, AR(1) 0.8, at the
  // optimum (where the Gram form cancels most) and at points around it.
  const LinearProblem problem = paper_problem(0.002, 0.8, 7);
  const std::vector<double> opt = least_squares_optimum(problem);
  for (double shift : {0.0, 1e-4, 1e-2, 0.3}) {
    std::vector<double> z = opt;
    for (double& v : z) v += shift;
    const double gram = problem.objective(z);
    const double two_pass = problem.sigma_two_pass(problem.physical(z));
    EXPECT_NEAR(gram / two_pass, 1.0, 1e-9) << "shift " << shift;
    EXPECT_NEAR(problem.objective_naive(z) / two_pass, 1.0, 1e-12);
  }
}

TEST(LinearProblem, PhysicalAndUnitBoxAreInverse) {
  const LinearProblem problem = paper_problem(0.002, 0.0, 3);
  const std::vector<double> z = {0.1, -0.4, 0.25};
  const Coefficients c = problem.physical(z);
  const std::vector<double> back = problem.unit_box(c);
  for (std::size_t j = 0; j < 3; ++j) EXPECT_NEAR(back[j], z[j], 1e-14);
  // The intercept is the mean residual of the physical model.
  EXPECT_NEAR(problem.residuals(c).mean(), 0.0, 1e-12);
}

TEST(LinearProblem, OptimumLiesInsideTheDataScaledBox) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const LinearProblem problem = paper_problem(0.003, 0.5, seed);
    for (double z : least_squares_optimum(problem)) EXPECT_LT(std::abs(z), 1.0);
  }
}

TEST(LinearProblem, LeastSquaresAgreesWithNormalEquations) {
  const LinearProblem problem = paper_problem(0.002, 0.0, 11);
  const Eigen::MatrixXd& x = problem.design();
  Eigen::MatrixXd a(x.rows(), x.cols() + 1);
  a << Eigen::VectorXd::Ones(x.rows()), x;
  const Eigen::VectorXd b = (a.transpose() * a).ldlt().solve(a.transpose() * problem.y());
  const Coefficients c = problem.physical(least_squares_optimum(problem));
  EXPECT_NEAR(c.intercept, b[0], 1e-8 * std::abs(b[0]));
  for (Eigen::Index j = 0; j < 3; ++j)
    EXPECT_NEAR(c.b[static_cast<std::size_t>(j)], b[j + 1], 1e-6 * std::abs(b[j + 1]));
}

TEST(LinearProblem, ConstantRegressorIsRejected) {
  Eigen::MatrixXd x(50, 2);
  Eigen::VectorXd y(50);
  for (int p = 0; p < 50; ++p) {
    x(p, 0) = 20.0;  // a constant temperature
    x(p, 1) = p;
    y[p] = p * 0.1;
  }
  try {
    LinearProblem problem(x, y, {"T", "t"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'T' is constant"), std::string::npos) << e.what();
  }
}

TEST(LinearProblem, CollinearTermsAreNamed) {
  Eigen::MatrixXd x(60, 3);
  Eigen::VectorXd y(60);
  for (int p = 0; p < 60; ++p) {
    x(p, 0) = p;
    x(p, 1) = std::sin(p);
    x(p, 2) = 2.0 * p + 5.0;  // T and this one are the same regressor
    y[p] = p;
  }
  try {
    LinearProblem problem(x, y, {"T", "grad", "t"});
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("collinear"), std::string::npos) << m;
    EXPECT_NE(m.find("T, t"), std::string::npos) << m;
  }
}

TEST(LinearProblem, TooFewPoints) {
  Eigen::MatrixXd x(4, 3);
  x << 1, 2, 3, 4, 5, 6, 7, 8, 10, 1, 0, 1;
  try {
    LinearProblem problem(x, Eigen::VectorXd::Ones(4), {"T", "T^2", "dT"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("only 4 averaged points"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace gyrotherm::fit
