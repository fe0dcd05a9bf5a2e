// What a record can tell: levels, range and r(T, t), and the flags `fit`
// raises on records that cannot support a coefficient — whose intervals must
// still hold the truth under the record's own noise.

#include "fit/record_support.h"

#include <gtest/gtest.h>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <algorithm>
#include <cmath>

#include "fit/model/formula.h"
#include "fit/pipeline.h"

namespace gyrotherm::fit {
namespace {

constexpr double kB1 = 0.02;  // °/h per °C

// A 1 Hz record with temperature temp(t), gyro = b1·T + white noise
// (0.016 °/h per sample) + a rate random walk K (°/h/√h).
template <class Temp>
Measurement record(double hours, Temp temp, double rrw, std::uint64_t seed) {
  Measurement m;
  m.file = "synthetic";
  boost::random::mt19937_64 rng(seed);
  boost::random::normal_distribution<double> normal;
  double walk = 0.0;
  for (int k = 0; k < static_cast<int>(hours * 3600); ++k) {
    const double t = k;
    walk += rrw / 60.0 * normal(rng);
    m.time_s.push_back(t);
    m.temp_c.push_back(temp(t));
    m.gyro_dph.push_back(kB1 * temp(t) + walk + 0.016 * normal(rng));
  }
  return m;
}

ModelFit fit_t(const Measurement& m) {
  return fit_model(prepare_data(m, {}), parse_formula("T"), find_engine("ols"), {});
}

TEST(RecordSupport, TwoPlateausAreTwoLevelsAndSaySo) {
  int covered = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const ModelFit f = fit_t(record(8.0, [](double t) { return t < 4 * 3600 ? 10.0 : 40.0; }, 1e-3, seed));
    EXPECT_EQ(f.support.temperature_levels, 2);
    EXPECT_NE(f.support.flags[0].find("2 temperature levels"), std::string::npos) << f.support.flags[0];
    covered += f.engine.inference.intervals[0].lower <= kB1 && kB1 <= f.engine.inference.intervals[0].upper;
  }
  EXPECT_GE(covered, 8);
}

TEST(RecordSupport, ANarrowWarmUpWithADriftIsFlaggedAndItsIntervalHoldsTheTruth) {
  // 0.3 °C warm-up over 2 h and a random-walk drift far larger than the
  // temperature's effect: the drift is read as temperature unless the
  // interval carries it.
  int covered = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const ModelFit f = fit_t(record(2.0, [](double t) { return 25.0 + 0.3 * (1 - std::exp(-t / 1800.0)); }, 0.05, seed));
    EXPECT_LT(f.support.temp_max_c - f.support.temp_min_c, 0.31);
    EXPECT_NE(f.support.flags[0].find("spans only"), std::string::npos) << f.support.flags[0];
    EXPECT_NE(f.support.flags[0].find("follows time"), std::string::npos) << f.support.flags[0];
    covered += f.engine.inference.intervals[0].lower <= kB1 && kB1 <= f.engine.inference.intervals[0].upper;
  }
  EXPECT_GE(covered, 8);
}

TEST(RecordSupport, ARampingCycleRaisesNoFlag) {
  const ModelFit f = fit_t(record(9.0, [](double t) { return 10.0 + 30.0 * std::sin(2 * M_PI * t / 10800.0); }, 0.0, 1));
  EXPECT_GE(f.support.temperature_levels, kMinTemperatureLevels);
  EXPECT_LT(std::abs(f.support.temp_time_correlation), 0.5);
  EXPECT_EQ(f.support.flags[0], "");
  EXPECT_NEAR(f.support.temp_min_c, -20.0, 0.1);
  EXPECT_NEAR(f.support.temp_max_c, 40.0, 0.1);
}

TEST(RecordSupport, ASteadyRampIsManyLevelsAndTwoPlateausHaveAGap) {
  // A 2 h ramp over 30 °C: every bin it crosses is a level, no gap.
  const ModelFit ramp = fit_t(record(2.0, [](double t) { return 10.0 + 30.0 * t / 7200.0; }, 0.0, 1));
  EXPECT_GE(ramp.support.temperature_levels, 30);
  EXPECT_LT(ramp.support.gap_to_c - ramp.support.gap_from_c, 1.0);
  ASSERT_EQ(ramp.support.reasons.size(), 1u);
  for (SupportReason r : ramp.support.reasons[0]) EXPECT_EQ(r, SupportReason::time_locked);
  // Two plateaus: two levels and the gap between them.
  const ModelFit two = fit_t(record(8.0, [](double t) { return t < 4 * 3600 ? 10.0 : 40.0; }, 1e-3, 1));
  EXPECT_NEAR(two.support.gap_from_c, 10.0, 0.5);
  EXPECT_NEAR(two.support.gap_to_c, 40.0, 0.5);
  const auto& why = two.support.reasons[0];
  EXPECT_NE(std::find(why.begin(), why.end(), SupportReason::few_levels), why.end());
  EXPECT_NE(std::find(why.begin(), why.end(), SupportReason::gap), why.end());
  EXPECT_NE(two.support.flags[0].find("no data between 10.0 and 40.0 °C"), std::string::npos) << two.support.flags[0];
  // A plateau with a tenth of the windows on a second one: under two levels.
  const ModelFit lopsided = fit_t(record(10.0, [](double t) { return t < 9 * 3600 ? 10.0 : 40.0; }, 1e-3, 1));
  EXPECT_LE(lopsided.support.temperature_levels, 2);
}

}  // namespace
}  // namespace gyrotherm::fit
