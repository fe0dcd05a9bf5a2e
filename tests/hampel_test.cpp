// Tests for fit/data/hampel.h: the centred and trailing windows' decisions and
// scales against the rule computed by brute force (each window's values
// sorted afresh, fit/data/median.h's median of the deviations), bit for bit,
// on records that keep the window in order most of the time (glitches,
// correlated noise whose sample-to-sample floor is far below its spread,
// quantised ties) and on quiet ones, with gaps and irregular sampling.

#include "fit/data/hampel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "fit/data/median.h"

namespace gyrotherm::fit {
namespace {

struct Record {
  std::vector<double> t, x;
};

// The rule of hampel.h on the values `window` for the sample x: (glitch, s).
std::pair<bool, double> brute_force(const HampelRule& rule, std::vector<double> window, double x) {
  const double m = median_in_place(window);
  for (double& v : window) v = std::abs(v - m);
  const double s = std::max(kMadToSigma * median_in_place(window), rule.floor_dph);
  const double deviation = std::abs(x - m);
  return {deviation > rule.threshold * s && deviation > rule.zero_dph, s};
}

// kind 0: quantised white noise with glitches; 1: AR(1) noise (φ = 0.98), whose
// floor from first differences is a fifth of its spread; 2: a few levels, ties everywhere.
Record make_record(std::uint64_t seed, int kind, std::size_t n) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> jitter(0.7, 1.3);
  std::bernoulli_distribution glitch(0.01), gap(0.002);
  std::uniform_int_distribution<int> level(0, 3);
  Record r;
  double t = 0.0, e = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    t += gap(rng) ? 40.0 : jitter(rng);
    double x = 0.0;
    if (kind == 0) x = std::round(4.0 * (gauss(rng) + 0.001 * t)) / 4.0 + (glitch(rng) ? 30.0 : 0.0);
    if (kind == 1) x = (e = 0.98 * e + 0.2 * gauss(rng));
    if (kind == 2) x = 0.5 * level(rng) + (glitch(rng) ? -9.0 : 0.0);
    r.t.push_back(t);
    r.x.push_back(x);
  }
  return r;
}

double floor_of(const Record& r) {
  std::vector<double> jumps;
  for (std::size_t k = 1; k < r.x.size(); ++k) jumps.push_back(std::abs(r.x[k] - r.x[k - 1]));
  const double median = median_in_place(jumps);
  return median > 0.0 ? kMadToSigma * median / std::sqrt(2.0) : 0.5;
}

TEST(CentredHampel, DecisionsAndScalesAreTheRuleComputedByBruteForce) {
  for (int kind = 0; kind < 3; ++kind)
    for (const double window_s : {5.0, 60.0}) {
      const Record r = make_record(10 + static_cast<std::uint64_t>(kind), kind, 3000);
      const HampelRule rule{8.0, floor_of(r), 1e-9};
      const std::size_t stride = 7;
      CentredHampel<std::size_t> filter(rule, window_s, stride);
      std::vector<std::size_t> order;
      std::vector<unsigned char> kept;
      const auto judged = [&](std::size_t k, bool keep) {
        order.push_back(k);
        kept.push_back(keep ? 1 : 0);
      };
      for (std::size_t k = 0; k < r.t.size(); ++k) filter.add(r.t[k], r.x[k], k, judged);
      filter.finish(judged);
      ASSERT_EQ(order.size(), r.t.size());
      std::vector<double> scales;
      std::size_t glitches = 0;
      for (std::size_t k = 0; k < r.t.size(); ++k) {
        ASSERT_EQ(order[k], k);
        std::vector<double> window;
        for (std::size_t j = 0; j < r.t.size(); ++j)
          if (std::abs(r.t[j] - r.t[k]) <= 0.5 * window_s) window.push_back(r.x[j]);
        if (window.size() < 3) {
          EXPECT_TRUE(kept[k]) << k;
          continue;
        }
        const auto [glitch, s] = brute_force(rule, window, r.x[k]);
        EXPECT_EQ(kept[k] == 0, glitch) << "kind " << kind << " sample " << k;
        glitches += glitch ? 1 : 0;
        if (k % stride == 0) scales.push_back(s);
      }
      EXPECT_EQ(filter.scales(), scales) << "kind " << kind;
      if (kind != 1) {
        EXPECT_GT(glitches, 5u);
      }
    }
}

TEST(TrailingHampel, DecisionsAreTheRuleComputedByBruteForce) {
  for (int kind = 0; kind < 3; ++kind) {
    const Record r = make_record(20 + static_cast<std::uint64_t>(kind), kind, 3000);
    const double window_s = 30.0;
    const HampelRule rule{8.0, floor_of(r), 1e-9};
    TrailingHampel filter(rule, window_s);
    for (std::size_t k = 0; k < r.t.size(); ++k) {
      std::vector<double> window;
      for (std::size_t j = 0; j <= k; ++j)
        if (r.t[k] - r.t[j] <= window_s) window.push_back(r.x[j]);
      const bool expected = window.size() >= 3 && brute_force(rule, window, r.x[k]).first;
      ASSERT_EQ(filter.is_glitch(r.t[k], r.x[k]), expected) << "kind " << kind << " sample " << k;
    }
  }
}

}  // namespace
}  // namespace gyrotherm::fit
