// The semi-separable whitener against the dense covariance it factors: the
// whitened identity is L⁻¹ of the dense Cholesky factor (so WᵀW = C⁻¹), the
// log-determinant is the dense one, and GLS equals the dense formula.

#include "fit/model/noise_whitening.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

// 300 windows of 100 s with gaps and short windows (a bursty logger's).
WindowGrid uneven_grid() {
  WindowGrid g;
  g.window_s = 100.0;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double t = 50.0;
  for (int i = 0; i < 300; ++i) {
    g.time_s.push_back(t);
    g.averaging_s.push_back(u(rng) < 0.1 ? 40.0 + 50.0 * u(rng) : 100.0);
    t += u(rng) < 0.05 ? 100.0 + 3000.0 * u(rng) : 100.0;
  }
  return g;
}

NoiseModel every_component() {
  NoiseModel m;
  m.amplitude = {4e-4 * 3600.0, 2e-7, 5e-7, 1e-12};  // white, flicker s², Gauss–Markov σ², random walk q_r
  m.flicker_tau_s = {100.0, 1000.0, 10000.0, 100000.0};
  m.gm_tau_s = 1800.0;
  return m;
}

Eigen::MatrixXd dense(const NoiseModel& m, const WindowGrid& g) {
  const auto n = static_cast<Eigen::Index>(g.size());
  return m.apply(g, Eigen::MatrixXd::Identity(n, n));
}

TEST(NoiseWhitening, WhitenedIdentityIsTheInverseCholeskyFactor) {
  const WindowGrid g = uneven_grid();
  for (int drop = -1; drop < kNoiseKinds; ++drop) {
    NoiseModel m = every_component();
    if (drop > 0) m.amplitude[static_cast<std::size_t>(drop)] = 0.0;  // white stays: C must be definite
    const Eigen::MatrixXd c = dense(m, g);
    const NoiseWhitener w(m, g);
    const auto n = static_cast<Eigen::Index>(g.size());
    const Eigen::MatrixXd z = w.whiten(Eigen::MatrixXd(Eigen::MatrixXd::Identity(n, n)));
    // zᵀz = C⁻¹, i.e. z C zᵀ = I.
    const Eigen::MatrixXd should_be_identity = z * c * z.transpose();
    EXPECT_LT((should_be_identity - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), 1e-8) << "drop " << drop;
    // Lower triangular: whitening is causal.
    EXPECT_LT(z.triangularView<Eigen::StrictlyUpper>().toDenseMatrix().cwiseAbs().maxCoeff(), 1e-12);
    const Eigen::LLT<Eigen::MatrixXd> llt(c);
    double logdet = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) logdet += 2.0 * std::log(llt.matrixLLT()(i, i));
    EXPECT_NEAR(w.log_determinant(), logdet, 1e-8 * std::abs(logdet)) << "drop " << drop;
  }
}

TEST(NoiseWhitening, SolveIsTheInverseCovariance) {
  const WindowGrid g = uneven_grid();
  const NoiseModel m = every_component();
  const Eigen::MatrixXd c = dense(m, g);
  const auto n = static_cast<Eigen::Index>(g.size());
  const Eigen::MatrixXd should_be_identity = NoiseWhitener(m, g).solve(c);
  EXPECT_LT((should_be_identity - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(NoiseWhitening, GlsEqualsTheDenseFormula) {
  const WindowGrid g = uneven_grid();
  const NoiseModel m = every_component();
  const auto n = static_cast<Eigen::Index>(g.size());
  Eigen::MatrixXd x(n, 2);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = g.time_s[static_cast<std::size_t>(i)];
    x(i, 0) = std::sin(t / 20000.0);
    x(i, 1) = t / 1e5;
    y[i] = 0.3 + 0.01 * x(i, 0) - 0.02 * x(i, 1) + 1e-3 * std::cos(t / 777.0);
  }
  const GlsFit fit = gls(NoiseWhitener(m, g), x, y);
  Eigen::MatrixXd design(n, 3);
  design << Eigen::VectorXd::Ones(n), x;
  const Eigen::MatrixXd ci = dense(m, g).inverse();
  const Eigen::MatrixXd info = design.transpose() * ci * design;
  const Eigen::VectorXd beta = info.ldlt().solve(design.transpose() * ci * y);
  EXPECT_LT((fit.beta - beta).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((fit.covariance - info.inverse()).cwiseAbs().maxCoeff() / info.inverse().cwiseAbs().maxCoeff(), 1e-8);
  const Eigen::VectorXd r = y - design * beta;
  EXPECT_NEAR(fit.whitened_residual.squaredNorm(), r.dot(ci * r), 1e-8 * r.dot(ci * r));
}

TEST(NoiseWhitening, ACovarianceThatIsNotDefiniteIsAFitError) {
  WindowGrid g;
  g.window_s = 100.0;
  g.time_s = {50.0, 150.0, 250.0};
  g.averaging_s = {100.0, 100.0, 100.0};
  NoiseModel m;  // no component at all: C = 0
  EXPECT_THROW(NoiseWhitener(m, g), FitError);
}

}  // namespace
}  // namespace gyrotherm::fit
