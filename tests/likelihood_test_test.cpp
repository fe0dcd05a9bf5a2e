// diagnose's likelihood test (studies/diagnose/likelihood_test.h): its
// p-values are uniform when the noise is the model's (one column and a grid
// of step positions), a loud step gets a p far below the bootstrap's 1/(B+1),
// and the single-column tail is the Beta law it claims.

#include "studies/diagnose/likelihood_test.h"

#include <gtest/gtest.h>

#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <vector>

#include "sim/util/random.h"

namespace gyrotherm::studies {
namespace {

fit::WindowGrid grid_of(int windows) {
  fit::WindowGrid g;
  g.window_s = 100.0;
  for (int i = 0; i < windows; ++i) {
    g.time_s.push_back(50.0 + 100.0 * i);
    g.averaging_s.push_back(100.0);
  }
  return g;
}

// White noise with a random walk and a Gauss–Markov process.
fit::NoiseModel coloured() {
  fit::NoiseModel m;
  m.amplitude = {1e-3 * 100.0, 0.0, 4e-7, 1e-11};
  m.gm_tau_s = 3000.0;
  return m;
}

Eigen::MatrixXd steps(int windows, int from, int to) {
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(windows, to - from);
  for (int k = from; k < to; ++k) x.col(k - from).tail(windows - k).setOnes();
  return x;
}

// White noise of 0.1 (°/h)²·s: windows of 100 s have variance 1e-3.
fit::NoiseModel white_noise() {
  fit::NoiseModel m;
  m.amplitude[fit::kWhite] = 0.1;
  return m;
}

// The model's one regressor, a slow sine.
Eigen::MatrixXd slow_sine(int l) {
  Eigen::MatrixXd model(l, 1);
  for (int i = 0; i < l; ++i) model(i, 0) = std::sin(i / 30.0);
  return model;
}

// `count` records of the noise m (the null), from `seed`.
std::vector<Eigen::VectorXd> null_records(const fit::NoiseModel& m, const fit::WindowGrid& g, int count,
                                          std::uint64_t seed) {
  Rng rng = make_rng(seed, 99);
  boost::random::normal_distribution<double> normal;
  std::vector<Eigen::VectorXd> out;
  for (int r = 0; r < count; ++r) out.push_back(m.draw(g, [&] { return normal(rng); }));
  return out;
}

TEST(LikelihoodTest, PValuesAreUniformUnderTheModelsNoise) {
  const int l = 200;
  const fit::WindowGrid g = grid_of(l);
  const fit::NoiseModel m = coloured();
  const fit::NoiseWhitener w(m, g);
  const Eigen::MatrixXd model = slow_sine(l);
  Eigen::MatrixXd column(l, 1);
  for (int i = 0; i < l; ++i) column(i, 0) = std::cos(i / 17.0) + 0.01 * i;
  const Eigen::MatrixXd positions = steps(l, 5, l - 5);
  const int replicates = 300;
  int below_single = 0, below_steps = 0, below_boot = 0, r = 0;
  for (const Eigen::VectorXd& y : null_records(m, g, replicates, 3)) {
    LikelihoodTest t(w, model, y);
    const std::size_t a = t.add(column);
    const std::size_t b = t.add(positions);
    t.calibrate(200, static_cast<std::uint64_t>(r++));
    below_single += t.score(a).p_value < 0.1;
    below_steps += t.score(b).p_value < 0.1;
    below_boot += t.score(b).p_bootstrap < 0.1;
    EXPECT_GT(t.score(b).tests, 2.0);
  }
  // 10 % of 300 = 30, binomial sd 5.2: within 3 sd.
  EXPECT_NEAR(below_single, 30, 16);
  EXPECT_NEAR(below_steps, 30, 16);
  EXPECT_NEAR(below_boot, 30, 16);
}

// Under white noise a step's positions are strongly correlated tests (their
// statistics a Brownian bridge): the effective number of tests grows as p
// falls, so n̂ is read from the draws' lower tail. From the mean of all
// draws it came out too small: 51 of these 300 p-values fell below 0.1
// (10 %: 30).
TEST(LikelihoodTest, StepPValuesHoldTheirLevelUnderWhiteNoise) {
  const int l = 200;
  const fit::WindowGrid g = grid_of(l);
  const fit::NoiseModel m = white_noise();
  const fit::NoiseWhitener w(m, g);
  const Eigen::MatrixXd positions = steps(l, 5, l - 5);
  int below_10 = 0, below_1 = 0, boot_below_1 = 0, r = 0;
  for (const Eigen::VectorXd& y : null_records(m, g, 300, 4)) {
    LikelihoodTest t(w, slow_sine(l), y);
    const std::size_t s = t.add(positions);
    t.calibrate(400, static_cast<std::uint64_t>(r++));
    below_10 += t.score(s).p_value < 0.1;
    below_1 += t.score(s).p_value < 0.01;
    boot_below_1 += t.score(s).p_bootstrap < 0.01;
  }
  EXPECT_NEAR(below_10, 30, 16);  // 3 binomial sd
  // At 1 % the draws' own share (exact for this noise, its resolution
  // 1/401) is the yardstick: here it puts 7 of these records below 0.01,
  // the tail's n̂ 9, the mean of all draws 12.
  EXPECT_LE(below_1, boot_below_1 + 3);
}

TEST(LikelihoodTest, ALoudStepHasAPFarBelowTheDrawsResolution) {
  const int l = 300;
  const fit::WindowGrid g = grid_of(l);
  const fit::NoiseModel m = coloured();
  const fit::NoiseWhitener w(m, g);
  Rng rng = make_rng(5, 99);
  boost::random::normal_distribution<double> normal;
  Eigen::VectorXd y = m.draw(g, [&] { return normal(rng); });
  const double sd = std::sqrt(m.amplitude[fit::kWhite] / 100.0);
  y.tail(130).array() += 8.0 * sd;
  LikelihoodTest t(w, Eigen::MatrixXd(l, 0), y);
  const std::size_t s = t.add(steps(l, 4, l - 4));
  t.calibrate(199, 1);
  EXPECT_EQ(t.score(s).best + 4, static_cast<std::size_t>(l - 130));
  EXPECT_LT(t.score(s).p_value, 1e-6);
  EXPECT_DOUBLE_EQ(t.score(s).p_bootstrap, 1.0 / 200.0);
}

// The family's effective number of tests from the same draws: two copies of
// one candidate are one test, two independent candidates two.
TEST(LikelihoodTest, TheFamilyCountsCorrelatedCandidatesOnce) {
  const int l = 300;
  const fit::WindowGrid g = grid_of(l);
  const fit::NoiseWhitener w(white_noise(), g);
  // Two independent random columns, and a record of the noise.
  const std::vector<Eigen::VectorXd> draws = null_records(white_noise(), g, 3, 9);
  const Eigen::MatrixXd a = draws[0], b = draws[1];
  const Eigen::VectorXd& y = draws[2];
  LikelihoodTest same(w, Eigen::MatrixXd(l, 0), y);
  same.add(a);
  same.add(a);
  same.calibrate(400, 1);
  LikelihoodTest apart(w, Eigen::MatrixXd(l, 0), y);
  apart.add(a);
  apart.add(b);
  apart.calibrate(400, 1);
  // The tail's estimate spreads about 1/√20 (22 %).
  EXPECT_GE(same.family_tests(), 1.0);  // at least the heaviest weight
  EXPECT_LE(same.family_tests(), 1.5);
  EXPECT_GE(apart.family_tests(), 1.4);
  EXPECT_LE(apart.family_tests(), 2.0);  // at most the sum of the weights
}

TEST(LikelihoodTest, SingleColumnTailIsBeta) {
  // ν = 3: g ~ Beta(1/2, 1), P(g ≥ x) = 1 − √x.
  EXPECT_NEAR(LikelihoodTest::single_p(0.25, 3.0), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(LikelihoodTest::single_p(0.0, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(LikelihoodTest::single_p(1.0, 10.0), 0.0);
}

// The autoregression of a whitened residual: none where it is white, the
// coefficient where it is an AR(1).
TEST(LikelihoodTest, TheResidualsAutoregressionIsFoundWhereThereIsOne) {
  Rng rng = make_rng(5, 99);
  boost::random::normal_distribution<double> normal;
  const int l = 2000;
  int empty = 0;
  for (int r = 0; r < 20; ++r) {
    Eigen::VectorXd e(l);
    for (int i = 0; i < l; ++i) e[i] = normal(rng);
    empty += residual_autoregression(e, 10).size() == 0;
  }
  EXPECT_GE(empty, 12);  // Akaike's criterion keeps a spurious order now and then
  Eigen::VectorXd a(l);
  a[0] = normal(rng);
  for (int i = 1; i < l; ++i) a[i] = 0.5 * a[i - 1] + normal(rng);
  const Eigen::VectorXd phi = residual_autoregression(a, 10);
  ASSERT_GE(phi.size(), 1);
  EXPECT_NEAR(phi[0], 0.5, 0.06);
  EXPECT_EQ(residual_autoregression(a, 0).size(), 0);
}

// A noise model that misses correlation at short lags (a Gauss–Markov
// process of 5 windows taken for white noise, as block means longer than
// its correlation time take it) makes the test too bold for a column with
// slow content; drawn through the residual's autoregression the bootstrap
// carries that correlation, and the p-values hold their level again (on
// these records 101 of 200 p-values fell below 0.1 without it, 16 with it).
TEST(LikelihoodTest, CorrelationTheModelMissesIsDrawnIntoTheNull) {
  const int l = 400;
  const fit::WindowGrid g = grid_of(l);
  fit::NoiseModel truth = white_noise();
  truth.amplitude[fit::kGaussMarkov] = 2.0 * truth.amplitude[fit::kWhite] / 100.0;
  truth.gm_tau_s = 500.0;
  fit::NoiseModel assumed = white_noise();
  assumed.amplitude[fit::kWhite] *= 3.0;  // the windows' variance, read as white
  const fit::NoiseWhitener w(assumed, g);
  Eigen::MatrixXd column(l, 1);
  for (int i = 0; i < l; ++i) column(i, 0) = std::sin(i / 9.0) + std::cos(i / 23.0);
  int plain = 0, sieved = 0, r = 0;
  for (const Eigen::VectorXd& y : null_records(truth, g, 200, 6)) {
    LikelihoodTest t(w, slow_sine(l), y);
    const std::size_t a = t.add(column);
    LikelihoodTest u(w, slow_sine(l), y);
    const std::size_t b = u.add(column);
    t.calibrate(400, static_cast<std::uint64_t>(r));
    const Eigen::VectorXd phi = residual_autoregression(fit::gls(w, slow_sine(l), y).whitened_residual, 20);
    u.calibrate(400, static_cast<std::uint64_t>(r++), phi);
    plain += t.score(a).p_value < 0.1;
    sieved += u.score(b).p_value < 0.1;
  }
  // 10 % of 200 = 20, binomial sd 4.2.
  EXPECT_GT(plain, 40) << "the misspecified model alone";
  EXPECT_NEAR(sieved, 20, 13);
}

}  // namespace
}  // namespace gyrotherm::studies
