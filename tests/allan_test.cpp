// Tests for sim/allan.h against analytic Allan variances: a rate ramp
// (σ²(τ) = a²τ²/2 exactly) and white noise (σ(τ) = s/√(τ/Δt)), plus the
// rounding/dropping rules and the coverage of the confidence band.

#include "sim/allan.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <gtest/gtest.h>

namespace gyrotherm::sim {
namespace {

std::vector<double> white_noise(std::size_t n, double std_dev, std::uint64_t seed) {
  boost::random::mt19937_64 rng(seed);
  boost::random::normal_distribution<double> normal(0.0, std_dev);
  std::vector<double> y(n);
  for (double& v : y) v = normal(rng);
  return y;
}

// y_k = offset + a·t_k, t_k = k·Δt. Adjacent τ-averages differ by exactly aτ, so
// σ²(τ) = (aτ)²/2 for every τ = mΔt.
std::vector<double> ramp(std::size_t n, double dt_s, double slope, double offset) {
  std::vector<double> y(n);
  for (std::size_t k = 0; k < n; ++k) y[k] = offset + slope * static_cast<double>(k) * dt_s;
  return y;
}

TEST(AllanDeviation, RampGivesExactAllanVariance) {
  const double dt_s = 0.5;
  const double slope = 0.37;  // rate units per second
  const std::vector<double> y = ramp(1000, dt_s, slope, 1.0e3);
  const std::vector<double> taus = {0.5, 1.0, 5.0, 50.0, 250.0};
  const std::vector<AllanPoint> points = allan_deviation(y, dt_s, taus);
  ASSERT_EQ(points.size(), taus.size());
  for (std::size_t i = 0; i < taus.size(); ++i) {
    EXPECT_DOUBLE_EQ(points[i].tau_s, taus[i]);
    const double expected = slope * taus[i] / std::sqrt(2.0);
    EXPECT_NEAR(points[i].deviation, expected, 1e-9 * expected) << "tau = " << taus[i];
  }
}

TEST(AllanDeviation, WhiteNoiseAveragesAsOneOverRootTau) {
  const double dt_s = 0.1;
  const double std_dev = 2.0;
  const std::size_t n = 200000;
  const std::vector<double> y = white_noise(n, std_dev, 42);
  const std::vector<double> taus = {0.1, 1.0, 10.0, 100.0};
  const std::vector<AllanPoint> points = allan_deviation(y, dt_s, taus);
  ASSERT_EQ(points.size(), taus.size());
  for (const AllanPoint& p : points) {
    const double m = std::round(p.tau_s / dt_s);
    const double expected = std_dev / std::sqrt(m);
    // The non-overlapping estimator from K = n/m clusters has K − 1 degrees of
    // freedom, so its deviation has relative std 1/√(2(K − 1)); the overlapping
    // one is at least as good. Allow 4 of those.
    const double clusters = std::floor(static_cast<double>(n) / m);
    const double tolerance = 4.0 / std::sqrt(2.0 * (clusters - 1.0));
    EXPECT_NEAR(p.deviation / expected, 1.0, tolerance) << "tau = " << p.tau_s;
    EXPECT_EQ(p.clusters, static_cast<std::size_t>(clusters));
    EXPECT_LT(p.lower, p.deviation);
    EXPECT_GT(p.upper, p.deviation);
  }
}

TEST(AllanDeviation, ConfidenceBandCoversTheTruthAboutTwoThirdsOfTheTime) {
  // For white noise the band is a 68.27 % interval: over R independent series
  // the number that contain the true σ is binomial(R, 0.6827), std √(R·0.68·0.32).
  const double dt_s = 1.0;
  const std::size_t n = 1000;
  const int runs = 1000;
  const std::vector<double> taus = {1.0, 10.0, 50.0};
  std::vector<int> covered(taus.size(), 0);
  for (int r = 0; r < runs; ++r) {
    const std::vector<double> y = white_noise(n, 1.0, 1000 + static_cast<std::uint64_t>(r));
    const std::vector<AllanPoint> points = allan_deviation(y, dt_s, taus);
    ASSERT_EQ(points.size(), taus.size());
    for (std::size_t i = 0; i < taus.size(); ++i) {
      const double truth = 1.0 / std::sqrt(taus[i]);
      if (points[i].lower <= truth && truth <= points[i].upper) ++covered[i];
    }
  }
  const double p = 0.6827;
  const double sigma = std::sqrt(runs * p * (1.0 - p));
  for (std::size_t i = 0; i < taus.size(); ++i)
    EXPECT_NEAR(covered[i], runs * p, 4.0 * sigma) << "tau = " << taus[i];
}

TEST(AllanDeviation, RoundsTauToWholeSamplesAndDropsWhatCannotBeEstimated) {
  const double dt_s = 0.5;
  const double slope = 2.0;
  const std::vector<double> y = ramp(100, dt_s, slope, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> taus = {
      0.2,   // m = 0.4 → 0: dropped
      0.74,  // m = 1.48 → 1
      1.26,  // m = 2.52 → 3
      1.4,   // m = 2.8 → 3 again: dropped
      25.0,  // m = 50: exactly 2 clusters of 100 samples
      25.5,  // m = 51: 1 cluster, dropped
      1e9,   // far too long
      -1.0,  // negative
      nan,
  };
  const std::vector<AllanPoint> points = allan_deviation(y, dt_s, taus);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_DOUBLE_EQ(points[0].tau_s, 0.5);
  EXPECT_DOUBLE_EQ(points[1].tau_s, 1.5);
  EXPECT_DOUBLE_EQ(points[2].tau_s, 25.0);
  EXPECT_EQ(points[0].clusters, 100u);
  EXPECT_EQ(points[1].clusters, 33u);
  EXPECT_EQ(points[2].clusters, 2u);
  // The rounded τ is the one the value belongs to: σ = aτ/√2 at τ = mΔt.
  for (const AllanPoint& p : points)
    EXPECT_NEAR(p.deviation, slope * p.tau_s / std::sqrt(2.0), 1e-9 * slope * p.tau_s);
}

TEST(AllanDeviation, TooShortSeriesGiveNothing) {
  const std::vector<double> one = {1.0};
  const std::vector<double> taus = {1.0};
  EXPECT_TRUE(allan_deviation(one, 1.0, taus).empty());
  const std::vector<double> three = {1.0, 2.0, 4.0};
  // m = 1: (ȳ₁ − ȳ₀)² = 1, (ȳ₂ − ȳ₁)² = 4, σ² = (1 + 4)/(2·2) = 1.25.
  const std::vector<AllanPoint> points = allan_deviation(three, 1.0, taus);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].deviation, std::sqrt(1.25), 1e-14);
}

TEST(OctaveTaus, LogSpacedWholeMultiplesUpToATenthOfTheRecord) {
  const std::vector<double> taus = octave_taus(1000000, 1.0, 5);
  // 10^(k/5) for k = 0 … 25: 1 … 1e5, all distinct after rounding.
  ASSERT_EQ(taus.size(), 26u);
  EXPECT_DOUBLE_EQ(taus.front(), 1.0);
  EXPECT_DOUBLE_EQ(taus.back(), 1.0e5);
  for (std::size_t k = 0; k < taus.size(); ++k) {
    const double exact = std::pow(10.0, static_cast<double>(k) / 5.0);
    EXPECT_LE(std::abs(taus[k] - exact), 0.5) << k;
  }

  const double dt_s = 0.01;
  const std::vector<double> fine = octave_taus(5000, dt_s, 10);
  ASSERT_FALSE(fine.empty());
  EXPECT_NEAR(fine.front(), dt_s, 1e-15);
  EXPECT_LE(fine.back(), 5000 * dt_s / 10.0 + 1e-12);
  for (std::size_t k = 0; k < fine.size(); ++k) {
    EXPECT_NEAR(fine[k] / dt_s, std::round(fine[k] / dt_s), 1e-9);
    if (k > 0) {
      EXPECT_GT(fine[k], fine[k - 1]);
    }
  }

  EXPECT_TRUE(octave_taus(9, 1.0).empty());
}

}  // namespace
}  // namespace gyrotherm::sim
