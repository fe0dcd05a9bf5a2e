// Tests for fit/data/outliers.h. Glitches are injected at known places into data of
// known noise; small cases are checked against medians and MADs worked out by
// hand in the comments.

#include "fit/data/outliers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <set>
#include <vector>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

constexpr double kQuantumDph = 0.05;

double quantised(double x) { return std::round(x / kQuantumDph) * kQuantumDph; }

Measurement record(std::vector<double> time_s, std::vector<double> gyro_dph) {
  Measurement m;
  m.file = "test.csv";
  m.temp_c.assign(time_s.size(), 25.0);
  m.time_s = std::move(time_s);
  m.gyro_dph = std::move(gyro_dph);
  return m;
}

std::vector<std::size_t> invalid_indices(const std::vector<unsigned char>& valid) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < valid.size(); ++k)
    if (!valid[k]) out.push_back(k);
  return out;
}

// `count` distinct indices in [first, last), at least `spacing` apart, sorted.
std::vector<std::size_t> spread_indices(std::mt19937_64& rng, std::size_t count, std::size_t first,
                                        std::size_t last, std::size_t spacing) {
  std::uniform_int_distribution<std::size_t> pick(first, last - 1);
  std::set<std::size_t> chosen;
  while (chosen.size() < count) {
    const std::size_t k = pick(rng);
    const auto near = chosen.lower_bound(k >= spacing ? k - spacing : 0);
    if (near != chosen.end() && *near <= k + spacing) continue;
    chosen.insert(k);
  }
  return {chosen.begin(), chosen.end()};
}

// 1 Hz quantised gyro output (multiples of 0.05 °/h, white noise σ = 0.02 °/h)
// on a slow thermal drift: −7 °/h plus a 0.8 °/h ramp and a 0.3 °/h swing.
Measurement quantised_ramp(std::mt19937_64& rng, std::size_t n) {
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<double> t(n), x(n);
  for (std::size_t k = 0; k < n; ++k) {
    t[k] = static_cast<double>(k);
    const double drift = -7.0 + 0.8 * t[k] / static_cast<double>(n) +
                         0.3 * std::sin(2.0 * std::numbers::pi * t[k] / 7200.0);
    x[k] = quantised(drift + noise(rng));
  }
  return record(std::move(t), std::move(x));
}

TEST(FlagOutliers, FindsEveryGlitchOnAQuantisedNoisyRampAndNothingElse) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    std::mt19937_64 rng(seed);
    Measurement m = quantised_ramp(rng, 20000);
    // Glitches anywhere, the first and last samples included.
    std::vector<std::size_t> glitches = spread_indices(rng, 30, 1, 19999, 3);
    glitches.insert(glitches.begin(), 0);
    glitches.push_back(19999);
    std::bernoulli_distribution sign(0.5);
    for (std::size_t k : glitches) m.gyro_dph[k] += sign(rng) ? 2.0 : -2.0;

    std::vector<unsigned char> valid(m.size(), 1);
    const OutlierReport report = flag_outliers(m, OutlierOptions{}, valid);
    EXPECT_EQ(invalid_indices(valid), glitches) << "seed " << seed;
    EXPECT_EQ(report.removed, glitches.size());
    std::vector<double> times;
    for (std::size_t k : glitches) times.push_back(m.time_s[k]);
    EXPECT_EQ(report.times_s, times);
    // The noise scale is of the order of the noise (σ = 0.02, quantum 0.05),
    // far from the 2 °/h glitches.
    EXPECT_GT(report.scale_dph, 0.01);
    EXPECT_LT(report.scale_dph, 0.1);
  }
}

TEST(FlagOutliers, NoGenuineSampleOnASteepRampIsFlagged) {
  // 0.6 °/h per minute, 30 times the noise per window: the median must follow it.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<double> t(3600), x(3600);
  for (std::size_t k = 0; k < t.size(); ++k) {
    t[k] = static_cast<double>(k);
    x[k] = quantised(0.01 * t[k] + noise(rng));
  }
  const Measurement m = record(t, x);
  std::vector<unsigned char> valid(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{}, valid);
  EXPECT_EQ(report.removed, 0u);
  EXPECT_TRUE(report.times_s.empty());
  EXPECT_EQ(std::count(valid.begin(), valid.end(), 0), 0);
}

TEST(FlagOutliers, QuantisedDataWithZeroMadUsesTheSmallestStepAsFloor) {
  // Mostly 0.10 °/h with 5 % one-quantum flicker: every window's MAD is 0 and
  // so is the median step, so the floor is the quantum, 0.05 °/h.
  std::mt19937_64 rng(5);
  std::bernoulli_distribution flicker(0.05);
  std::vector<double> t(5000), x(5000);
  for (std::size_t k = 0; k < t.size(); ++k) {
    t[k] = static_cast<double>(k);
    x[k] = flicker(rng) ? 0.15 : 0.10;
  }
  const std::vector<std::size_t> glitches = {100, 1234, 1236, 4000};
  x[100] = 2.10;
  x[1234] = -1.90;
  x[1236] = 2.15;
  x[4000] = 0.55;  // 9 quanta: above 8 × 0.05
  const Measurement m = record(t, x);
  std::vector<unsigned char> valid(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{}, valid);
  EXPECT_NEAR(report.floor_dph, 0.05, 1e-12);
  EXPECT_NEAR(report.scale_dph, 0.05, 1e-12);
  EXPECT_EQ(invalid_indices(valid), glitches);  // the flicker is kept
}

TEST(FlagOutliers, HandComputedOddWindow) {
  // All 9 samples in one window. Sorted: 0 0 0 0 0.1 0.1 0.1 0.1 5 → median 0.1.
  // |x − 0.1| sorted: 0 0 0 0 0.1 0.1 0.1 0.1 4.9 → MAD 0.1, local scale 0.14826.
  // Steps: 0.1 ×6, 4.9, 5 → median 0.1 → floor 1.4826 · 0.1 / √2 = 0.10484.
  // 4.9 > 8 · 0.14826 = 1.186: only the 5 goes.
  const Measurement m = record({0, 1, 2, 3, 4, 5, 6, 7, 8}, {0, 0.1, 0, 0.1, 5, 0, 0.1, 0, 0.1});
  std::vector<unsigned char> valid(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{.window_s = 100.0}, valid);
  EXPECT_EQ(invalid_indices(valid), (std::vector<std::size_t>{4}));
  EXPECT_NEAR(report.floor_dph, 1.4826 * 0.1 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(report.scale_dph, 1.4826 * 0.1, 1e-12);
}

TEST(FlagOutliers, HandComputedEvenWindow) {
  // Sorted: 1 2 3 4 5 6 7 100 → median 4.5. |x − 4.5| sorted:
  // 0.5 0.5 1.5 1.5 2.5 2.5 3.5 95.5 → MAD (1.5 + 2.5)/2 = 2, scale 2.9652.
  // Steps 1 1 1 96 95 1 1 → median 1 → floor 1.0484. 95.5 > 8 · 2.9652 = 23.7.
  const Measurement m = record({0, 1, 2, 3, 4, 5, 6, 7}, {1, 2, 3, 4, 100, 5, 6, 7});
  std::vector<unsigned char> valid(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{.window_s = 100.0}, valid);
  EXPECT_EQ(invalid_indices(valid), (std::vector<std::size_t>{4}));
  EXPECT_NEAR(report.scale_dph, 1.4826 * 2.0, 1e-12);
  EXPECT_NEAR(report.floor_dph, 1.4826 / std::sqrt(2.0), 1e-12);

  // A threshold above 95.5 / 2.9652 = 32.2 keeps it.
  std::vector<unsigned char> all(m.size(), 1);
  EXPECT_EQ(flag_outliers(m, OutlierOptions{.window_s = 100.0, .threshold = 33.0}, all).removed,
            0u);
}

TEST(FlagOutliers, ScaleOfWhiteNoiseIsItsSigma) {
  // Gaussian σ = 1: both the floor (from first differences) and the local MAD
  // estimate σ; the MAD of 61 samples has a standard error of about 0.16 σ, the
  // median over the record much less.
  std::mt19937_64 rng(21);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> t(20000), x(20000);
  for (std::size_t k = 0; k < t.size(); ++k) {
    t[k] = static_cast<double>(k);
    x[k] = noise(rng);
  }
  const Measurement m = record(t, x);
  std::vector<unsigned char> valid(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{}, valid);
  EXPECT_NEAR(report.floor_dph, 1.0, 0.03);
  EXPECT_NEAR(report.scale_dph, 1.0, 0.05);
  EXPECT_EQ(report.removed, 0u);  // 8σ: none in 20000 Gaussian samples
}

TEST(FlagOutliers, TheWindowIsInSeconds) {
  // A burst of 4 equal glitches at 1 Hz: a ±5 s window (11 samples) outvotes it,
  // a ±2 s window (5 samples) is mostly burst and takes it for signal.
  std::mt19937_64 rng(8);
  Measurement m = quantised_ramp(rng, 600);
  for (std::size_t k = 300; k < 304; ++k) m.gyro_dph[k] += 2.0;
  std::vector<unsigned char> valid(m.size(), 1);
  flag_outliers(m, OutlierOptions{.window_s = 10.0}, valid);
  EXPECT_EQ(invalid_indices(valid), (std::vector<std::size_t>{300, 301, 302, 303}));

  std::vector<unsigned char> narrow(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{.window_s = 4.0}, narrow);
  EXPECT_LT(report.removed, 4u);
}

TEST(FlagOutliers, IrregularSamplingAndGapsAreWindowedByTime) {
  // 10 Hz for 300 s, a 1000 s gap, 10 Hz again; glitches beside the gap and at
  // the ends. The default 60 s window holds about 600 samples.
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<double> t, x;
  for (std::size_t k = 0; k < 6000; ++k) {
    const double time_s = 0.1 * static_cast<double>(k) + (k >= 3000 ? 1000.0 : 0.0);
    t.push_back(time_s);
    x.push_back(quantised(-7.0 + 1e-4 * time_s + noise(rng)));
  }
  const std::vector<std::size_t> glitches = {0, 1500, 2999, 3000, 3001, 5999};
  for (std::size_t k : glitches) x[k] -= 2.0;
  const Measurement m = record(t, x);
  std::vector<unsigned char> valid(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{}, valid);
  EXPECT_EQ(invalid_indices(valid), glitches);
  EXPECT_EQ(report.removed, glitches.size());
}

TEST(FlagOutliers, SamplesAlreadyInvalidAreLeftAlone) {
  std::mt19937_64 rng(4);
  Measurement m = quantised_ramp(rng, 2000);
  m.gyro_dph[500] += 2.0;
  m.gyro_dph[900] += 2.0;
  std::vector<unsigned char> valid(m.size(), 1);
  valid[500] = 0;  // a glitch already removed
  valid[700] = 0;  // an ordinary sample removed for another reason
  const OutlierReport report = flag_outliers(m, OutlierOptions{}, valid);
  EXPECT_EQ(invalid_indices(valid), (std::vector<std::size_t>{500, 700, 900}));
  EXPECT_EQ(report.removed, 1u);
  EXPECT_EQ(report.times_s, (std::vector<double>{900.0}));
}

TEST(FlagOutliers, TooFewSamplesAreNotJudged) {
  const Measurement m = record({0, 1}, {0, 100});
  std::vector<unsigned char> valid(m.size(), 1);
  EXPECT_EQ(flag_outliers(m, OutlierOptions{}, valid).removed, 0u);
  EXPECT_EQ(valid, (std::vector<unsigned char>{1, 1}));
}

TEST(FlagOutliers, ConstantDataFlagsNothing) {
  const Measurement m = record({0, 1, 2, 3, 4, 5}, {0.1, 0.1, 0.1, 0.1, 0.1, 0.1});
  std::vector<unsigned char> valid(m.size(), 1);
  const OutlierReport report = flag_outliers(m, OutlierOptions{}, valid);
  EXPECT_EQ(report.removed, 0u);
  EXPECT_EQ(report.floor_dph, 0.0);
}

TEST(FlagOutliers, BadOptionsAreRejectedByName) {
  const Measurement m = record({0, 1, 2}, {0, 0, 0});
  std::vector<unsigned char> valid(m.size(), 1);
  for (double w : {0.0, -60.0, std::nan("")}) {
    try {
      flag_outliers(m, OutlierOptions{.window_s = w}, valid);
      ADD_FAILURE() << "window_s " << w << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("window_s"), std::string::npos) << e.what();
    }
  }
  try {
    flag_outliers(m, OutlierOptions{.threshold = 0.0}, valid);
    ADD_FAILURE() << "threshold 0 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--outlier-threshold 0"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(OutlierOptions{}.validate());
}

}  // namespace
}  // namespace gyrotherm::fit
