// Bias steps in a model's residual (studies/diagnose/steps): the level-shift
// statistic against ordinary least squares where they must agree, the
// bootstrap test's level on white and on slow (flicker-like) noise, its power
// and placement on a real step, and the placebo spread against its analytic
// value.

#include "studies/diagnose/steps.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>

namespace gyrotherm::studies {
namespace {

constexpr Eigen::Index kWindows = 200;

std::vector<double> window_times(Eigen::Index l) {
  std::vector<double> t(static_cast<std::size_t>(l));
  for (Eigen::Index i = 0; i < l; ++i) t[static_cast<std::size_t>(i)] = 100.0 * static_cast<double>(i) + 50.0;
  return t;
}

// A linear trend as the model (one regressor; the intercept is implicit).
Eigen::MatrixXd ramp_design(Eigen::Index l) {
  Eigen::MatrixXd d(l, 1);
  for (Eigen::Index i = 0; i < l; ++i) d(i, 0) = static_cast<double>(i) / static_cast<double>(l);
  return d;
}

Eigen::VectorXd white(Eigen::Index l, double sigma, boost::random::mt19937_64& rng) {
  boost::random::normal_distribution<double> n(0.0, sigma);
  Eigen::VectorXd x(l);
  for (Eigen::Index i = 0; i < l; ++i) x[i] = n(rng);
  return x;
}

// Flicker-like noise: a sum of AR(1) processes with time constants one per
// decade from 1 to 1000 windows and equal variance per decade (a 1/f spectrum
// over three decades), plus a white floor.
Eigen::VectorXd flicker(Eigen::Index l, double sigma, boost::random::mt19937_64& rng) {
  boost::random::normal_distribution<double> n(0.0, 1.0);
  Eigen::VectorXd x = white(l, sigma, rng);
  for (const double tau : {1.0, 10.0, 100.0, 1000.0}) {
    const double phi = std::exp(-1.0 / tau);
    const double innovation = sigma * std::sqrt(1.0 - phi * phi);
    double s = sigma * n(rng);  // stationary start
    for (Eigen::Index i = 0; i < l; ++i) {
      s = phi * s + innovation * n(rng);
      x[i] += s;
    }
  }
  return x;
}

StepSearch quick_search(std::uint64_t seed) {
  StepSearch s;
  s.replicates = 199;
  s.seed = seed;
  return s;
}

TEST(Steps, AStepInWhiteNoiseIsFoundWhereItIs) {
  boost::random::mt19937_64 rng(11);
  const auto t = window_times(kWindows);
  const Eigen::MatrixXd d = ramp_design(kWindows);
  int found = 0;
  for (const Eigen::Index at : {40, 90, 150}) {
    Eigen::VectorXd y = white(kWindows, 1.0, rng) + 2.0 * d.col(0);
    y.tail(kWindows - at).array() += 2.0;  // two noise standard deviations
    const auto steps = find_steps(t, d, y, quick_search(static_cast<std::uint64_t>(at)));
    ASSERT_FALSE(steps.empty()) << "step at window " << at;
    EXPECT_LE(std::abs(static_cast<Eigen::Index>(steps.front().index) - at), 2) << "step at window " << at;
    EXPECT_LT(steps.front().p_value, 0.01);
    EXPECT_GE(steps.front().p_value, 1.0 / 200.0);  // the resolution of 199 replicates
    EXPECT_DOUBLE_EQ(steps.front().time_s, 100.0 * static_cast<double>(steps.front().index));  // between two windows
    found += steps.size() == 1 ? 1 : 0;
  }
  EXPECT_GE(found, 2) << "a second, false step beside a real one";
}

// A hop and a hop back mask each other: with one step taken out, the other
// is read as random walk (a large q) and the first no longer stands out.
// Binary segmentation's weakness (steps.h); well above the noise both are
// found.
TEST(Steps, TwoStepsAreBothFoundInTimeOrder) {
  boost::random::mt19937_64 rng(5);
  const Eigen::MatrixXd d(kWindows, 0);
  Eigen::VectorXd y = white(kWindows, 1.0, rng);
  y.tail(kWindows - 60).array() += 6.0;
  y.tail(kWindows - 140).array() += -6.0;
  const auto steps = find_steps(window_times(kWindows), d, y, quick_search(3));
  ASSERT_GE(steps.size(), 2U);
  EXPECT_NEAR(static_cast<double>(steps[0].index), 60.0, 2.0);
  EXPECT_NEAR(static_cast<double>(steps[1].index), 140.0, 2.0);
}

// With no random walk (q → 0) the local level model is a constant mean and
// white noise, and the GLS t-statistic of a step is the ordinary one: the
// step's least-squares t jointly with the model, σ̂ from the model alone.
TEST(Steps, WithoutARandomWalkTheLevelShiftTIsTheLeastSquaresT) {
  boost::random::mt19937_64 rng(3);
  const Eigen::MatrixXd d = ramp_design(kWindows);
  Eigen::MatrixXd a(kWindows, 2);
  a.col(0).setOnes();
  a.col(1) = d.col(0);
  Eigen::VectorXd y = white(kWindows, 1.0, rng) + 3.0 * d.col(0);
  y.tail(kWindows - 120).array() += 0.8;
  const Eigen::VectorXd t = level_shift_t(y, a, 1e-12);
  const Eigen::VectorXd e = y - a * a.colPivHouseholderQr().solve(y);
  const double sigma = std::sqrt(e.squaredNorm() / (kWindows - 2));
  for (const Eigen::Index k : {4, 30, 119, 120, 121, 196}) {
    Eigen::MatrixXd with_step(kWindows, 3);
    with_step.leftCols(2) = a;
    with_step.col(2).setZero();
    with_step.col(2).tail(kWindows - k).setOnes();
    const Eigen::VectorXd beta = with_step.colPivHouseholderQr().solve(y);
    const double se = sigma * std::sqrt((with_step.transpose() * with_step).inverse()(2, 2));
    EXPECT_NEAR(t[k], beta[2] / se, 1e-6 * std::max(1.0, std::abs(beta[2] / se))) << "step before window " << k;
  }
  EXPECT_EQ(t[3], 0.0);  // fewer than 4 windows before
  EXPECT_EQ(t[kWindows - 3], 0.0);
}

TEST(Steps, TheFittedRandomWalkRatioIsRecovered) {
  boost::random::mt19937_64 rng(8);
  boost::random::normal_distribution<double> n(0.0, 1.0);
  for (const double q : {0.01, 0.1, 1.0}) {
    Eigen::VectorXd y(4000);
    double level = 0.0;
    for (Eigen::Index i = 0; i < y.size(); ++i) {
      y[i] = level + n(rng);
      level += std::sqrt(q) * n(rng);
    }
    EXPECT_NEAR(std::log(fit_level_q(y)), std::log(q), 0.35) << "q = " << q;
  }
  EXPECT_LT(fit_level_q(white(4000, 1.0, rng)), 1e-3);
}

// Under the null the p-value is about uniform: the share of records whose
// best step has p < α is about α.
TEST(Steps, WhiteNoiseGivesUniformPValues) {
  boost::random::mt19937_64 rng(21);
  const Eigen::MatrixXd d = ramp_design(kWindows);
  constexpr int kTrials = 200;
  int below_005 = 0, below_05 = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::VectorXd y = white(kWindows, 1.0, rng);
    StepSearch s;
    s.max_steps = 1;
    s.replicates = 99;
    s.seed = static_cast<std::uint64_t>(trial + 1);
    s.alpha = 0.05;
    below_005 += find_steps(window_times(kWindows), d, y, s).empty() ? 0 : 1;
    s.alpha = 0.5;
    below_05 += find_steps(window_times(kWindows), d, y, s).empty() ? 0 : 1;
  }
  const double share_005 = below_005 / static_cast<double>(kTrials);
  const double share_05 = below_05 / static_cast<double>(kTrials);
  // Binomial(200, p) spreads: 0.05 ± 0.015, 0.5 ± 0.035; bounds about 2.5 σ.
  EXPECT_GE(share_005, 0.015);
  EXPECT_LE(share_005, 0.09);
  EXPECT_GE(share_05, 0.41);
  EXPECT_LE(share_05, 0.59);
}

TEST(Steps, CleanWhiteRecordsRarelyShowAStep) {
  boost::random::mt19937_64 rng(33);
  const Eigen::MatrixXd d = ramp_design(kWindows);
  int flagged = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::VectorXd y = white(kWindows, 1.0, rng) + d.col(0);
    flagged += find_steps(window_times(kWindows), d, y, quick_search(static_cast<std::uint64_t>(trial + 1))).empty()
                   ? 0
                   : 1;
  }
  // α = 0.01: 1 expected, P(Binomial(100, 0.01) > 4) ≈ 0.003.
  EXPECT_LE(flagged, 4);
}

// Slow noise fits a step as well as a small real step does; a test that takes
// the residual for white (or AR(1)) noise calls steps in it. Against a local
// level model the test is anti-conservative on flicker spanning the record's
// own scale (steps.h): about 7 % at α = 0.01 on this noise.
TEST(Steps, SlowNoiseIsNotTakenForSteps) {
  boost::random::mt19937_64 rng(44);
  const Eigen::MatrixXd d = ramp_design(kWindows);
  int flagged = 0;
  constexpr int kTrials = 60;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::VectorXd y = flicker(kWindows, 1.0, rng);
    flagged += find_steps(window_times(kWindows), d, y, quick_search(static_cast<std::uint64_t>(trial + 1))).empty()
                   ? 0
                   : 1;
  }
  // 7 % expected: P(Binomial(60, 0.07) > 10) ≈ 0.01.
  EXPECT_LE(flagged, 10);
}

// With white noise of variance σ² and a model of the mean and the real step
// at a, a placebo step fitted after window k < a is the difference of the
// means of windows [0, k) and [k, a), of variance σ²·(1/k + 1/(a − k)) (and
// σ²·(1/(k − a) + 1/(l − k)) after a); the placebo spread is the root mean
// square of that over the placebo windows.
TEST(Steps, PlaceboSpreadMatchesItsAnalyticValueOnWhiteNoise) {
  boost::random::mt19937_64 rng(55);
  constexpr Eigen::Index l = 400;
  constexpr std::size_t at = 200;
  const Eigen::MatrixXd none(l, 0);
  double expected = 0.0;
  int n = 0;
  for (Eigen::Index k = 4; k + 4 <= l; ++k) {
    if (std::abs(k - static_cast<Eigen::Index>(at)) < 10) continue;
    const auto a = static_cast<Eigen::Index>(at);
    expected += k < a ? 1.0 / static_cast<double>(k) + 1.0 / static_cast<double>(a - k)
                      : 1.0 / static_cast<double>(k - a) + 1.0 / static_cast<double>(l - k);
    ++n;
  }
  expected = std::sqrt(expected / n);
  double mean_square = 0.0;
  constexpr int kTrials = 200;
  for (int trial = 0; trial < kTrials; ++trial) {
    Eigen::VectorXd y = white(l, 1.0, rng);
    y.tail(l - static_cast<Eigen::Index>(at)).array() += 3.0;  // the real step, excluded from the placebos
    Eigen::MatrixXd with_step(l, 1);
    with_step.setZero();
    with_step.col(0).tail(l - static_cast<Eigen::Index>(at)).setOnes();
    const double sd = placebo_step_sd(with_step, y, at);
    mean_square += sd * sd;
  }
  EXPECT_NEAR(std::sqrt(mean_square / kTrials), expected, 0.05 * expected);
}

TEST(Steps, TooShortAResidualHasNoSteps) {
  const Eigen::MatrixXd d(6, 0);
  Eigen::VectorXd y(6);
  y << 0, 0, 0, 5, 5, 5;
  EXPECT_TRUE(find_steps(window_times(6), d, y).empty());
}

}  // namespace
}  // namespace gyrotherm::studies
