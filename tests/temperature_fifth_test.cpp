// T^5 (sim/effects/temperature_fifth.cpp): its regressor by hand, and the
// effect end to end: simulated hidden on the cycle, fitted, diagnosed,
// compensated with, exported in C and refused by the cubic firmwares.

#include <gtest/gtest.h>

#include "effect_round_trip.h"
#include "sim/effects/effect.h"

namespace gyrotherm {
namespace {

TEST(TemperatureFifth, IsTheFifthPowerOfT) {
  const effects::Effect* e = effects::find("T^5");
  ASSERT_NE(e, nullptr);
  effects::EffectSeries s;
  s.time_s = {0.0, 100.0, 200.0};
  s.temp_c = {-2.0, 0.5, 30.0};
  EXPECT_EQ(effects::regressor_values(*e, s, 0.0), (std::vector<double>{-32.0, 0.03125, 24300000.0}));
  EXPECT_EQ(e->temperature_power, 5);
  EXPECT_TRUE(e->hidden());
}

// 1e-10 °/h/°C⁵ is 0.037 °/h at the cycle's 51.5 °C. (Over the cycle's
// −5.6..51.5 °C, T^3, T^4 and T^5 are nearly proportional; diagnose says so
// beside naming T^5 first.)
TEST(TemperatureFifth, WorksEndToEnd) {
  testing::expect_round_trip({.scenario = "cycle", .term = "T^5", .coefficient = 1e-10});
}

}  // namespace
}  // namespace gyrotherm
