// The model's 95 % band and its coefficients' covariance (fit/model_band.h):
// its diagonal gives the fit's own intervals, and over seeds the band holds
// the true bias where the record has data, with the true model.

#include "fit/model_band.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "cli_runner.h"
#include "fit/engines/ols.h"
#include "fit/model/formula.h"
#include "sim/config_loader.h"
#include "sim/simulator.h"
#include "studies/simulated.h"

namespace gyrotherm::fit {
namespace {

using gyrotherm::testing::source_path;

struct Simulated {
  sim::SimulationResult record;
  PreparedData data;
};

Simulated simulated_cycle(std::uint64_t seed) {
  sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  sc.seed = seed;
  Simulated s{sim::Simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(source_path("scenarios/gyro.toml"))).run(), {}};
  s.data = prepare_data(studies::measurement_of(s.record, "cycle"), PipelineOptions{});
  return s;
}

// The mean of the true bias over window p (its samples: centre ± window/2).
double true_window_mean(const Simulated& s, std::size_t p) {
  const double centre = s.data.series.time_s[p], half = 0.5 * s.data.series.window_s;
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < s.record.rows(); ++i)
    if (s.record.time_s[i] >= centre - half && s.record.time_s[i] < centre + half) {
      sum += s.record.bias_true_dph[i];
      ++n;
    }
  return sum / n;
}

// The covariance's diagonal is the fit's own: ols's intervals under the
// identified noise (intervals=model) are t·√V_jj, each term's widest variance
// among the noise models at that model's dof: the same here, the column of
// ones (orthogonal to the centred terms) changing nothing.
TEST(ModelBand, ItsDiagonalGivesTheFitsIntervals) {
  const Simulated s = simulated_cycle(3);
  const auto terms = parse_formula("T + T^2 + dT");
  EngineSettings settings;
  settings.options["intervals"] = "model";
  const ModelFit fit = fit_model(s.data, terms, find_engine("ols"), settings);
  const std::optional<CoefficientCovariance> cov = coefficient_covariance(s.data, terms, fit.parameters);
  ASSERT_TRUE(cov.has_value());
  ASSERT_EQ(cov->to_physical.rows(), 4);
  for (std::size_t j = 0; j < terms.size(); ++j) {
    const double fit_half = 0.5 * (fit.engine.inference.intervals[j].upper - fit.engine.inference.intervals[j].lower);
    Eigen::VectorXd w = Eigen::VectorXd::Zero(4);
    w[static_cast<Eigen::Index>(j) + 1] = 1.0;
    const double half = cov->half_width(w);
    EXPECT_NEAR(half / fit_half, 1.0, 1e-6) << terms[j]->name;
  }
  // The band at a window is the interval of the model's value there, finite and above 0.
  const Band band = model_band(*cov, s.data, terms, fit.parameters);
  ASSERT_EQ(band.half_width_dph.size(), s.data.series.size());
  EXPECT_TRUE(std::all_of(band.half_width_dph.begin(), band.half_width_dph.end(),
                          [](double h) { return h > 0.0 && std::isfinite(h); }));
  EXPECT_GE(band.smallest_dof, 1.0);
}

// Over seeds the band holds the true window-mean bias at the coldest, the
// middle and the hottest window: 95 % nominal; at least 76 of the 90 asked
// (84 %). Measured: 109 of 120 over 40 seeds (91 %): 38, 35 and 36 of 40 at
// the coldest, middle and hottest window; the middle window's errors spread
// 1.3 times its band's (a ramp's middle, where the dT regressor, formed from
// the sampled temperature, is least like the true rate).
TEST(ModelBand, IntervalsCoverTheTrueBiasOverSeeds) {
  const auto terms = parse_formula("T + T^2 + dT");
  int covered = 0, asked = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const Simulated s = simulated_cycle(seed);
    const ModelFit fit = fit_model(s.data, terms, find_engine("ols"), {});
    const std::optional<CoefficientCovariance> cov = coefficient_covariance(s.data, terms, fit.parameters);
    ASSERT_TRUE(cov.has_value()) << "seed " << seed;
    const std::vector<double> band = model_band(*cov, s.data, terms, fit.parameters).half_width_dph;
    const std::vector<double>& temp = s.data.series.temp_c;
    std::vector<std::size_t> order(temp.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return temp[a] < temp[b]; });
    for (const std::size_t p : {order.front(), order[order.size() / 2], order.back()}) {
      ++asked;
      covered += std::abs(fit.fitted_dph[p] - true_window_mean(s, p)) <= band[p];
    }
  }
  RecordProperty("covered", covered);
  EXPECT_GE(covered, 76) << "of " << asked;
}

// Too few windows to identify the noise (8.8 h in 4400 s windows: 7, for
// four coefficients): no covariance, not a made-up one.
TEST(ModelBand, NoneWhereTheNoiseCannotBeIdentified) {
  sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  const sim::SimulationResult r = sim::Simulator(sc, sim::load_rig(sc.rig_file), sim::load_gyro(source_path("scenarios/gyro.toml"))).run();
  PipelineOptions coarse;
  coarse.averaging.window_s = 4400.0;
  const PreparedData few = prepare_data(studies::measurement_of(r, "cycle"), coarse);
  ASSERT_LT(few.series.size(), 8u);
  const auto terms = parse_formula("T + T^2 + dT");
  EXPECT_FALSE(coefficient_covariance(few, terms, default_parameters(terms)).has_value());
}

}  // namespace
}  // namespace gyrotherm::fit
