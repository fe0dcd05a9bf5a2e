// The parametric bootstrap of ols's coefficients (fit/model/noise_bootstrap.h):
// with the noise known exactly it has the sandwich's covariance; the
// amplitudes' uncertainty widens it; of several structures the widest
// interval is taken; it is deterministic in its seed; and its intervals cover on the cycle
// (the fast version of results/ols_coverage.md's bootstrap rows).

#include "fit/model/noise_bootstrap.h"

#include <gtest/gtest.h>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>

#include "fit/engines/ols.h"
#include "sim/config_loader.h"
#include "sim/util/input_error.h"
#include "studies/coverage/interval_coverage.h"

namespace gyrotherm::fit {
namespace {

// 300 windows of 100 s with a gap, and a centred design of a trend and a cycle.
WindowGrid grid_with_gap() {
  WindowGrid g;
  g.window_s = 100.0;
  for (int i = 0; i < 300; ++i) {
    g.time_s.push_back(50.0 + 100.0 * i + (i >= 150 ? 3000.0 : 0.0));
    g.averaging_s.push_back(100.0);
  }
  return g;
}

Eigen::MatrixXd centred_design(const WindowGrid& g) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(g.size()), 2);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const double t = g.time_s[static_cast<std::size_t>(i)];
    x(i, 0) = t / 3600.0;
    x(i, 1) = std::sin(2.0 * M_PI * t / 20000.0);
  }
  return x.rowwise() - x.colwise().mean();
}

// White + Gauss–Markov (1 h), amplitudes known exactly (no covariance).
NoiseModel known_noise() {
  NoiseModel m;
  m.amplitude[kWhite] = 3600.0 * 1e-8;  // N = 1e-4 °/√h
  m.amplitude[kGaussMarkov] = 4e-7;
  m.gm_tau_s = 3600.0;
  m.present = {true, false, true, false};
  m.identified = {true, false, true, false};
  return m;
}

Eigen::MatrixXd sample_covariance(const Eigen::MatrixXd& draws) {
  const Eigen::MatrixXd c = draws.rowwise() - draws.colwise().mean();
  return c.transpose() * c / static_cast<double>(draws.rows() - 1);
}

TEST(NoiseBootstrap, WithTheNoiseKnownItHasTheSandwichCovariance) {
  const WindowGrid g = grid_with_gap();
  const Eigen::MatrixXd x = centred_design(g);
  const NoiseModel m = known_noise();
  const NoiseBootstrap boot = noise_bootstrap(m, g, x, 4000, 7);
  const Eigen::MatrixXd v = noise_sandwich(m, g, x).covariance;
  ASSERT_EQ(boot.errors.size(), 1u);
  const Eigen::MatrixXd s = sample_covariance(boot.errors.front());
  // 4000 draws: a variance is known to √(2/4000) = 2.2 %.
  for (Eigen::Index j = 0; j < 2; ++j) EXPECT_NEAR(s(j, j) / v(j, j), 1.0, 0.08) << j;
  EXPECT_NEAR(s(0, 1) / std::sqrt(s(0, 0) * s(1, 1)), v(0, 1) / std::sqrt(v(0, 0) * v(1, 1)), 0.05);
  // The interval is centred on the estimate, about ±1.96 sd wide.
  const auto [lo, hi] = boot.interval(0, 1.0);
  EXPECT_NEAR((hi - lo) / 2.0 / std::sqrt(v(0, 0)), 1.96, 0.15);
  EXPECT_NEAR((hi + lo) / 2.0, 1.0, 0.1 * (hi - lo));
}

TEST(NoiseBootstrap, UncertainAmplitudesWidenTheIntervalAndBoundsHold) {
  const WindowGrid g = grid_with_gap();
  const Eigen::MatrixXd x = centred_design(g);
  NoiseModel sure = known_noise();
  NoiseModel unsure = sure;
  // The Gauss–Markov variance known to a factor of 2 (sd of its log 0.7).
  unsure.covariance(kGaussMarkov, kGaussMarkov) = std::pow(0.7 * sure.amplitude[kGaussMarkov], 2);
  const auto width = [&](const NoiseModel& m) {
    const auto [lo, hi] = noise_bootstrap(m, g, x, 4000, 3).interval(0, 0.0);
    return hi - lo;
  };
  EXPECT_GT(width(unsure), 1.05 * width(sure));

  // A component the record does not pin down never exceeds its 95 % bound.
  NoiseModel bounded = unsure;
  bounded.identified[kGaussMarkov] = false;
  bounded.upper_bound[kGaussMarkov] = 1.2 * sure.amplitude[kGaussMarkov];
  boost::random::mt19937_64 rng(5);
  boost::random::normal_distribution<double> n01;
  const std::function<double()> normal = [&] { return n01(rng); };
  int raised = 0;
  for (int k = 0; k < 500; ++k) {
    const double a = plausible_noise(bounded, g, normal).amplitude[kGaussMarkov];
    EXPECT_LE(a, bounded.upper_bound[kGaussMarkov] * (1 + 1e-12));
    raised += a > sure.amplitude[kGaussMarkov];
  }
  EXPECT_GT(raised, 100);  // the cap bites, not the draw's absence
}

TEST(NoiseBootstrap, OfSeveralStructuresEachCoefficientTakesTheWidest) {
  const WindowGrid g = grid_with_gap();
  const Eigen::MatrixXd x = centred_design(g);
  NoiseModel best = known_noise();
  // A random walk the record supports as well: far more power at the trend's scale.
  NoiseModel walk;
  walk.amplitude[kWhite] = best.amplitude[kWhite];
  walk.amplitude[kRandomWalk] = 1e-10;
  walk.present = {true, false, false, true};
  walk.identified = walk.present;
  const auto width = [](const NoiseBootstrap& b) {
    const auto [lo, hi] = b.interval(0, 0.0);
    return hi - lo;
  };
  const NoiseBootstrap alone = noise_bootstrap(best, g, x, 2000, 4);
  const NoiseBootstrap walk_alone = noise_bootstrap(walk, g, x, 2000, 4);
  ASSERT_GT(width(walk_alone), 1.5 * width(alone));  // the case is a real one
  best.alternatives = {walk};
  const NoiseBootstrap both = noise_bootstrap(best, g, x, 2000, 4);
  ASSERT_EQ(both.errors.size(), 2u);
  EXPECT_NEAR(width(both) / width(walk_alone), 1.0, 0.1);
  // A coefficient at 2 sd of the best structure's spread: significant there, not under the walk.
  const double at = 0.5 * width(alone);
  EXPECT_LT(alone.p_value(0, at), 0.06);
  EXPECT_GT(both.p_value(0, at), 0.2);
  EXPECT_NEAR(both.p_value(0, at), walk_alone.p_value(0, at), 0.05);
}

TEST(NoiseBootstrap, TheSeedDecidesTheDraws) {
  const WindowGrid g = grid_with_gap();
  const Eigen::MatrixXd x = centred_design(g);
  const NoiseModel m = known_noise();
  EXPECT_EQ(noise_bootstrap(m, g, x, 200, 1).errors.front(), noise_bootstrap(m, g, x, 200, 1).errors.front());
  EXPECT_NE(noise_bootstrap(m, g, x, 200, 1).errors.front(), noise_bootstrap(m, g, x, 200, 2).errors.front());
  // And the option is checked: fewer than 100 draws cannot give a 95 % interval.
  OlsOptions o;
  o.intervals = "bootstrap";
  o.draws = 50;
  EXPECT_THROW(o.validate(), InputError);
}

TEST(NoiseBootstrap, IntervalsCoverOnTheCycleUnderGaussMarkovNoise) {
  const std::string dir = std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/";
  const sim::Scenario scenario = sim::load_scenario(dir + "cycle.toml");
  const sim::RigConfig rig = sim::load_rig(scenario.rig_file);
  sim::GyroConfig g = sim::load_gyro(scenario.gyro_file);
  g.noise = studies::noise_variant("white+gm3600", g.noise);
  studies::CoverageOptions options;
  options.seeds = 40;
  options.intervals = "bootstrap";
  const studies::Coverage c = studies::interval_coverage(scenario, rig, g, options);
  ASSERT_EQ(c.terms.size(), 3u);
  for (const studies::TermCoverage& t : c.terms) {
    EXPECT_GE(t.covered, 33) << t.term;  // ≥ 82.5 % of 40 (at 95 %: 7 misses in 0.5 % of studies)
    EXPECT_LT(t.half_width, 4.0 * t.sd) << t.term;
  }
}

}  // namespace
}  // namespace gyrotherm::fit
