// The noise model: window covariances against the kernels' integrals, REML
// identification of known noise, and intervals that cover under coloured
// noise (the fast version of results/ols_coverage.md).

#include "fit/model/noise_model.h"
#include "fit/model/noise_whitening.h"

#include <gtest/gtest.h>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <algorithm>
#include <cmath>
#include <functional>

#include "sim/config_loader.h"
#include "sim/util/input_error.h"
#include "studies/coverage/interval_coverage.h"

namespace gyrotherm::fit {
namespace {

// Irregular window centres (a gap between the third and fourth), Δ = 100 s.
WindowGrid irregular_grid() {
  WindowGrid g;
  g.window_s = 100.0;
  g.time_s = {50.0, 160.0, 300.0, 420.0, 900.0, 1000.0};
  g.averaging_s = {100.0, 90.0, 100.0, 80.0, 100.0, 100.0};
  return g;
}

// (1/Δ²) ∫∫ k(u, v) over windows i and j by the midpoint rule.
template <class Kernel>
double window_integral(const WindowGrid& g, std::size_t i, std::size_t j, Kernel k) {
  constexpr int n = 600;
  const double h = g.window_s / n;
  double sum = 0.0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      sum += k(g.time_s[i] - g.window_s / 2 + (a + 0.5) * h, g.time_s[j] - g.window_s / 2 + (b + 0.5) * h);
  return sum * h * h / (g.window_s * g.window_s);
}

TEST(NoiseModel, WindowCovariancesAreTheKernelsIntegrals) {
  const WindowGrid g = irregular_grid();
  const auto n = static_cast<Eigen::Index>(g.size());
  NoiseModel m;
  m.gm_tau_s = 150.0;
  const Eigen::MatrixXd gm = m.apply(g, Eigen::MatrixXd::Identity(n, n), kGaussMarkov);
  const Eigen::MatrixXd rw = m.apply(g, Eigen::MatrixXd::Identity(n, n), kRandomWalk);
  const Eigen::MatrixXd white = m.apply(g, Eigen::MatrixXd::Identity(n, n), kWhite);
  const double t0 = g.time_s.front() - g.window_s / 2;
  for (std::size_t i = 0; i < g.size(); ++i) {
    for (std::size_t j = 0; j < g.size(); ++j) {
      const auto ii = static_cast<Eigen::Index>(i), jj = static_cast<Eigen::Index>(j);
      const double e = window_integral(g, i, j, [](double u, double v) { return std::exp(-std::abs(u - v) / 150.0); });
      EXPECT_NEAR(gm(ii, jj), e, 2e-4) << i << "," << j;
      const double r = window_integral(g, i, j, [&](double u, double v) { return std::min(u, v) - t0; });
      EXPECT_NEAR(rw(ii, jj) / r, 1.0, 1e-4) << i << "," << j;
      EXPECT_DOUBLE_EQ(white(ii, jj), i == j ? 1.0 / g.averaging_s[i] : 0.0);
    }
  }
  // The operator is symmetric (C = Cᵀ) for every component together.
  m.amplitude = {1.0, 0.5, 0.3, 1e-3};
  m.flicker_tau_s = {100.0, 1000.0};
  const Eigen::MatrixXd all = m.apply(g, Eigen::MatrixXd::Identity(n, n));
  EXPECT_LT((all - all.transpose()).cwiseAbs().maxCoeff(), 1e-12);
}

// Draws from the model (what the step test's bootstrap uses) have the
// model's window covariance: 20 000 draws on the irregular grid match C within
// sampling error, except the random walk's −q_r·Δ/6 on the diagonal, which the
// draw leaves out by design (noise_model.h).
TEST(NoiseModel, DrawsHaveTheModelsCovariance) {
  const WindowGrid g = irregular_grid();
  const auto n = static_cast<Eigen::Index>(g.size());
  NoiseModel m;
  m.amplitude = {100.0, 0.5, 0.3, 2e-4};
  m.flicker_tau_s = {30.0, 300.0, 3000.0};
  m.gm_tau_s = 500.0;
  Eigen::MatrixXd c = m.apply(g, Eigen::MatrixXd::Identity(n, n));
  c.diagonal().array() += m.amplitude[kRandomWalk] * g.window_s / 6.0;
  boost::random::mt19937_64 rng(5);
  boost::random::normal_distribution<double> normal;
  const std::function<double()> draw_normal = [&] { return normal(rng); };
  constexpr int kDraws = 20000;
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < kDraws; ++k) {
    const Eigen::VectorXd x = m.draw(g, draw_normal);
    s += x * x.transpose();
  }
  s /= kDraws;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      // The sampling sd of a covariance estimate: √((C_ii C_jj + C_ij²)/draws); 4 of them.
      const double sd = std::sqrt((c(i, i) * c(j, j) + c(i, j) * c(i, j)) / kDraws);
      EXPECT_NEAR(s(i, j), c(i, j), 4.0 * sd) << i << "," << j;
    }
  // One Gauss–Markov process alone (τ = 3 windows), twelve regular windows:
  // its correlation at every lag, where a draw with the wrong memory shows.
  WindowGrid r;
  r.window_s = 100.0;
  for (int i = 0; i < 12; ++i) {
    r.time_s.push_back(50.0 + 100.0 * i);
    r.averaging_s.push_back(100.0);
  }
  NoiseModel gm;
  gm.amplitude = {0.0, 0.0, 1.0, 0.0};
  gm.gm_tau_s = 300.0;
  const Eigen::MatrixXd cg = gm.apply(r, Eigen::MatrixXd::Identity(12, 12));
  Eigen::MatrixXd sg = Eigen::MatrixXd::Zero(12, 12);
  for (int k = 0; k < kDraws; ++k) {
    const Eigen::VectorXd x = gm.draw(r, draw_normal);
    sg += x * x.transpose();
  }
  sg /= kDraws;
  for (Eigen::Index lag = 1; lag < 12; ++lag) {
    const double sd = std::sqrt((cg(0, 0) * cg(lag, lag) + cg(0, lag) * cg(0, lag)) / kDraws);
    EXPECT_NEAR(sg(0, lag), cg(0, lag), 4.0 * sd) << "lag " << lag;
    EXPECT_NEAR(sg(5, 5 + std::min<Eigen::Index>(lag, 6)), cg(5, 5 + std::min<Eigen::Index>(lag, 6)), 4.0 * sd);
  }
}

// Window means of white noise (ARW N) plus, optionally, a rate random walk K,
// around a temperature-like regressor; REML on y with that regressor.
struct Synthetic {
  WindowGrid grid;
  Eigen::MatrixXd design;
  Eigen::VectorXd y;
};
Synthetic synthetic(double arw, double rrw, std::uint64_t seed, int windows = 400) {
  Synthetic s;
  s.grid.window_s = 100.0;
  boost::random::mt19937_64 rng(seed);
  boost::random::normal_distribution<double> normal;
  s.design.resize(windows, 1);
  s.y.resize(windows);
  double walk = 0.0;
  for (int i = 0; i < windows; ++i) {
    const double t = 100.0 * i + 50.0;
    s.grid.time_s.push_back(t);
    s.grid.averaging_s.push_back(100.0);
    s.design(i, 0) = 30.0 * std::sin(2 * M_PI * t / 20000.0);
    walk += rrw / 60.0 * std::sqrt(100.0) * normal(rng);  // q_r = K²/3600 per second
    s.y[i] = 1e-4 * s.design(i, 0) + walk + 60.0 * arw / std::sqrt(100.0) * normal(rng);
  }
  return s;
}

TEST(NoiseModel, WhiteNoiseIsIdentifiedAndNothingElseClaimed) {
  // 20 seeds: a right 95 % interval misses more than 4 times with
  // probability 1.6 %.
  int covered = 0, claimed = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Synthetic s = synthetic(3e-4, 0.0, seed);
    const NoiseModel m = identify_noise(s.grid, s.design, s.y);
    const NoiseParameter arw = m.parameters().front();
    ASSERT_EQ(arw.name, "arw");
    covered += arw.identified && arw.lower <= 3e-4 && 3e-4 <= arw.upper;
    claimed += m.identified[kFlicker] || m.identified[kGaussMarkov] || m.identified[kRandomWalk];
  }
  EXPECT_GE(covered, 16);
  EXPECT_LE(claimed, 3);
}

TEST(NoiseModel, RandomWalkPowerIsRecovered) {
  // What intervals depend on is the slow power, however the model splits it
  // between random walk and flicker: the variance it predicts for a trend
  // fitted to the record (the regressor most exposed to it) is within a
  // factor of 2 of the true model's in most seeds, and the random walk itself
  // is named in most. Over 11 h a random walk can look like flicker: in 2 of
  // these 10 seeds the record prefers flicker and the trend's variance is
  // 7–11 times too small; 2 more estimate K at half its value.
  int close = 0, named = 0;
  std::vector<double> ratios;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Synthetic s = synthetic(3e-4, 2e-3, seed);
    const NoiseModel m = identify_noise(s.grid, s.design, s.y);
    NoiseModel truth;
    truth.amplitude = {3600.0 * 3e-4 * 3e-4, 0.0, 0.0, 2e-3 * 2e-3 / 3600.0};
    Eigen::MatrixXd trend(static_cast<Eigen::Index>(s.grid.size()), 1);
    for (std::size_t i = 0; i < s.grid.size(); ++i) trend(static_cast<Eigen::Index>(i), 0) = s.grid.time_s[i];
    trend.array() -= trend.mean();
    const double ratio = noise_sandwich(m, s.grid, trend).covariance(0, 0) /
                         noise_sandwich(truth, s.grid, trend).covariance(0, 0);
    close += ratio > 0.5 && ratio < 2.5;
    ratios.push_back(ratio);
    named += m.identified[kRandomWalk];
  }
  std::sort(ratios.begin(), ratios.end());
  EXPECT_GT(ratios[4], 0.5);
  EXPECT_LT(ratios[5], 2.0);
  EXPECT_GE(close, 6);
  EXPECT_GE(named, 7);
}

TEST(NoiseModel, EachColumnsCovarianceIsTheSameWhateverColumnsItIsTakenWith) {
  // What identify_noise's passes over a long record's block-mean weights (a
  // few columns at a time, in bounded memory) rest on: C·x column by column
  // is C·x, to the bit, and applied into a matrix it is the same.
  const WindowGrid g = irregular_grid();
  NoiseModel m;
  m.amplitude = {3.0, 0.5, 0.2, 1e-4};
  m.flicker_tau_s = {100.0, 1000.0, 10000.0};
  m.gm_tau_s = 300.0;
  Eigen::MatrixXd x(static_cast<Eigen::Index>(g.size()), 5);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (Eigen::Index c = 0; c < x.cols(); ++c) x(i, c) = std::sin(1.3 * static_cast<double>(i) + 0.7 * static_cast<double>(c));
  const Eigen::MatrixXd all = m.apply(g, x);
  Eigen::MatrixXd into = Eigen::MatrixXd::Constant(2, 9, 7.0);
  m.apply(g, x, into);
  EXPECT_TRUE((into.array() == all.array()).all());
  for (int kind = -1; kind < kNoiseKinds; ++kind) {
    const Eigen::MatrixXd whole = m.apply(g, x, kind);
    for (Eigen::Index c = 0; c < x.cols(); ++c) {
      const Eigen::MatrixXd one = m.apply(g, Eigen::MatrixXd(x.middleCols(c, std::min<Eigen::Index>(2, x.cols() - c))), kind);
      EXPECT_TRUE((one.col(0).array() == whole.col(c).array()).all()) << "kind " << kind << ", column " << c;
    }
  }
}

TEST(NoiseModel, ALongRecordIsIdentifiedInPasses) {
  // 20 000 windows: C is applied to the block-mean weights in passes of
  // fewer than the 64 columns; the white noise is recovered as on a short record.
  const Synthetic s = synthetic(3e-4, 0.0, 3, 20000);
  const NoiseModel m = identify_noise(s.grid, s.design, s.y);
  const NoiseParameter arw = m.parameters().front();
  EXPECT_TRUE(arw.identified);
  EXPECT_LE(arw.lower, 3e-4);
  EXPECT_GE(arw.upper, 3e-4);
  EXPECT_EQ(m.blocks, 64u);
}

TEST(NoiseModel, TooFewWindowsAreRefused) {
  const Synthetic s = synthetic(3e-4, 0.0, 1, 5);
  EXPECT_THROW(identify_noise(s.grid, s.design, s.y), InputError);
}

// The fast coverage study: 40 seeds of the simulated cycle with the default
// gyro (white + flicker) and with white + a 1 h Gauss–Markov process. A true
// 95 % interval covers ≥ 34 of 40 with probability 0.98; 32 allows for the
// paper's model missing the sensor lag's d2T (results/ols_coverage.md). The
// intervals must also not be vacuous: half-width under 4 sd (they take the
// widest of the noise models the record supports alike, so T and T² run
// wide).
TEST(NoiseModel, IntervalsCoverUnderColouredNoise) {
  const std::string dir = std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/";
  const sim::Scenario scenario = sim::load_scenario(dir + "cycle.toml");
  const sim::RigConfig rig = sim::load_rig(scenario.rig_file);
  const sim::GyroConfig gyro = sim::load_gyro(scenario.gyro_file);
  for (const char* variant : {"white+flicker", "white+gm3600"}) {
    sim::GyroConfig g = gyro;
    g.noise = studies::noise_variant(variant, gyro.noise);
    studies::CoverageOptions options;
    options.seeds = 40;
    const studies::Coverage c = studies::interval_coverage(scenario, rig, g, options);
    ASSERT_EQ(c.terms.size(), 3u);
    for (const studies::TermCoverage& t : c.terms) {
      EXPECT_GE(t.covered, 32) << variant << " " << t.term;
      EXPECT_LT(t.half_width, 4.0 * t.sd) << variant << " " << t.term;
    }
  }
}

// The 95 % bounds of a Gauss–Markov process the record did not identify are
// where −2 log L has risen by 3.84 at each correlation time they are stated
// at (log-spaced between Δ and the span, √(Δ·span) among them), and those
// are the models diagnose's test holds under (plausible_models). Checked
// against the exact likelihood of the windows (GLS, noise_whitening.h),
// independent of the block means the bounds were found on: each raised
// model costs a few units, not the tens a bound found at another time costs
// (one found at the whole span, which the intercept absorbs, and applied at
// √(Δ·span) once vetoed most steps under flicker noise).
TEST(NoiseModel, AnUnidentifiedGaussMarkovBoundIsALikelihoodBoundAtItsStatedTime) {
  std::vector<double> rise;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Synthetic s = synthetic(3e-4, 0.0, seed);
    const NoiseModel m = identify_noise(s.grid, s.design, s.y);
    if (m.present[kGaussMarkov]) continue;
    const double span = 100.0 * static_cast<double>(s.grid.size()), middle = std::sqrt(100.0 * span);
    ASSERT_EQ(m.gm_bounds.size(), 5u);
    EXPECT_TRUE(std::any_of(m.gm_bounds.begin(), m.gm_bounds.end(), [&](const auto& b) {
      return std::abs(b.first - middle) < 1.0 && b.second == m.upper_bound[kGaussMarkov];
    }));
    const double base = gls(NoiseWhitener(m, s.grid), s.design, s.y).log_likelihood;
    int raised_models = 0;
    for (const NoiseModel& raised : plausible_models(m, s.grid)) {
      if (!raised.present[kGaussMarkov]) continue;
      ++raised_models;
      EXPECT_GT(raised.gm_tau_s, 100.0);
      EXPECT_LT(raised.gm_tau_s, span);
      rise.push_back(-2.0 * (gls(NoiseWhitener(raised, s.grid), s.design, s.y).log_likelihood - base));
    }
    EXPECT_EQ(raised_models, 5);
  }
  ASSERT_GE(rise.size(), 75u);
  std::sort(rise.begin(), rise.end());
  const double median = rise[rise.size() / 2];
  EXPECT_GT(median, 1.0);
  EXPECT_LT(median, 8.0);
  EXPECT_LT(rise[rise.size() * 9 / 10], 15.0);
}

}  // namespace
}  // namespace gyrotherm::fit
