// The gls engine against the dense GLS formula, its intervals by their
// coverage over seeds of a known noise, and its width against ols's under the
// same honest covariance.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <memory>

#include "fit/engines/engine.h"
#include "fit/engines/ols.h"
#include "fit/model/noise_model.h"
#include "fit_test_data.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

constexpr std::size_t kWindows = 320;

WindowGrid grid_of(const AveragedSeries& s) {
  WindowGrid g;
  g.window_s = 100.0;
  g.time_s = s.time_s;
  g.averaging_s.assign(s.size(), 100.0);
  return g;
}

// White noise of 0.002 °/h per window and a random walk that wanders 0.01 °/h over the record.
NoiseModel walk() {
  NoiseModel m;
  m.amplitude[kWhite] = 0.002 * 0.002 * 100.0;
  m.amplitude[kRandomWalk] = 0.01 * 0.01 / (kWindows * 100.0);
  return m;
}

NoiseModel gauss_markov() {
  NoiseModel m;
  m.amplitude[kWhite] = 0.002 * 0.002 * 100.0;
  m.amplitude[kGaussMarkov] = 0.004 * 0.004;
  m.gm_tau_s = 3600.0;
  return m;
}

// The paper's model on the synthetic cycle with a draw of `noise`, the noise attached as identified.
// The registry's gls with covariance=COVARIANCE ("" for the default).
FitResult gls_fit(const LinearProblem& problem, const std::string& covariance = "") {
  EngineSettings settings;
  if (!covariance.empty()) settings.options["covariance"] = covariance;
  return find_engine("gls").make(settings)->fit(problem);
}

LinearProblem problem_with(const NoiseModel& noise, std::uint64_t seed) {
  const AveragedSeries s = synthetic_cycle(kWindows);
  const DerivedSeries d = derive(s, DerivativeMode::central);
  const std::vector<const Term*> terms = parse_formula("T + T^2 + dT");
  const Eigen::MatrixXd x = design_matrix(d, terms, default_parameters(terms));
  const WindowGrid g = grid_of(s);
  boost::random::mt19937_64 rng(seed);
  boost::random::normal_distribution<double> normal;
  const Eigen::VectorXd e = noise.draw(g, [&] { return normal(rng); });
  Eigen::VectorXd y(x.rows());
  for (Eigen::Index p = 0; p < x.rows(); ++p) y[p] = kB0 + kB1 * x(p, 0) + kB2 * x(p, 1) + kB3 * x(p, 2) + e[p];
  LinearProblem problem(x, y, {"T", "T^2", "dT"});
  problem.attach_noise(std::make_shared<NoiseContext>(NoiseContext{noise, g}));
  return problem;
}

TEST(GlsEngine, EqualsTheDenseFormula) {
  const NoiseModel noise = gauss_markov();
  const LinearProblem problem = problem_with(noise, 3);
  const FitResult r = gls_fit(problem, "model");
  const Eigen::MatrixXd& x = problem.scaled_design();
  const auto l = x.rows();
  Eigen::MatrixXd design(l, x.cols() + 1);
  design << Eigen::VectorXd::Ones(l), x;
  const Eigen::MatrixXd c = noise.apply(problem.noise()->grid, Eigen::MatrixXd::Identity(l, l));
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(c);
  const Eigen::MatrixXd info = design.transpose() * ldlt.solve(design);
  const Eigen::VectorXd beta = info.ldlt().solve(design.transpose() * ldlt.solve(problem.centred_y()));
  const Eigen::MatrixXd cov = info.inverse();
  const Coefficients coef = problem.physical(r.z);
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const auto jj = static_cast<std::size_t>(j);
    EXPECT_NEAR(r.z[jj] * problem.half_width()[j], beta[j + 1], 1e-8 * std::abs(beta[j + 1])) << j;
    // Half-width: t₉₅ (dof large: about 1.97) times the dense standard error.
    const double se = std::sqrt(cov(j + 1, j + 1)) / problem.scale()[j];
    const double half = (r.inference.intervals[jj].upper - r.inference.intervals[jj].lower) / 2.0;
    EXPECT_GT(half / se, 1.959) << j;
    EXPECT_LT(half / se, 2.05) << j;
    EXPECT_NEAR((r.inference.intervals[jj].upper + r.inference.intervals[jj].lower) / 2.0, coef.b[jj], 1e-9 * std::abs(coef.b[jj]));
  }
  EXPECT_EQ(r.engine, "gls");
  // Not the least-squares optimum: a σ at or above it.
  EXPECT_GE(r.objective, problem.objective(least_squares_optimum(problem)) * (1.0 - 1e-12));
}

TEST(GlsEngine, IntervalsCoverAndAreNarrowerThanLeastSquaresUnderRandomWalk) {
  const double truth[3] = {kB1, kB2, kB3};
  int covered[3] = {0, 0, 0};
  double gls_width[3] = {0, 0, 0}, ols_width[3] = {0, 0, 0};
  const int seeds = 300;
  for (int s = 1; s <= seeds; ++s) {
    const LinearProblem problem = problem_with(walk(), static_cast<std::uint64_t>(s));
    const FitResult g = gls_fit(problem, "model");
    const FitResult o = OlsEngine({.intervals = "model"}).fit(problem);
    for (int j = 0; j < 3; ++j) {
      covered[j] += g.inference.intervals[j].lower <= truth[j] && truth[j] <= g.inference.intervals[j].upper;
      gls_width[j] += g.inference.intervals[j].upper - g.inference.intervals[j].lower;
      ols_width[j] += o.inference.intervals[j].upper - o.inference.intervals[j].lower;
    }
  }
  for (int j = 0; j < 3; ++j) {
    // 95 % of 300: binomial sd 1.3 %; 91–99 % holds a right interval with room.
    EXPECT_GE(covered[j], 0.91 * seeds) << j;
    EXPECT_LE(covered[j], 0.99 * seeds) << j;
  }
  // The random walk's slow power hits T and T² (they vary as slowly); GLS weighs it out.
  EXPECT_LT(gls_width[0], 0.9 * ols_width[0]);
  EXPECT_LT(gls_width[1], 0.9 * ols_width[1]);
  EXPECT_LE(gls_width[2], 1.001 * ols_width[2]);
}

TEST(GlsEngine, WithoutAnIdentifiedNoiseItIsLeastSquaresAndSaysSo) {
  const LinearProblem problem = paper_problem(0.002, 0.5, 4);
  const FitResult g = gls_fit(problem);
  const FitResult o = OlsEngine().fit(problem);
  EXPECT_EQ(g.z, o.z);
  EXPECT_EQ(g.engine, "gls");
  EXPECT_EQ(g.detail.kind, RunDetail::Kind::gls_without_noise);
  EXPECT_NE(run_text(g).find("no noise model identified"), std::string::npos) << run_text(g);
}

TEST(GlsEngine, RefusesAnUnknownCovariance) {
  EXPECT_THROW(gls_fit(paper_problem(0.002), "sandwich"), InputError);
}

}  // namespace
}  // namespace gyrotherm::fit
