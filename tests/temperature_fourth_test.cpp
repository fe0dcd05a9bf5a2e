// T^4 (sim/effects/temperature_fourth.cpp): its regressor by hand, and the
// effect end to end: simulated hidden on the cycle, fitted, diagnosed,
// compensated with, exported in C and refused by the cubic firmwares.

#include <gtest/gtest.h>

#include "effect_round_trip.h"
#include "sim/effects/effect.h"

namespace gyrotherm {
namespace {

TEST(TemperatureFourth, IsTheFourthPowerOfT) {
  const effects::Effect* e = effects::find("T^4");
  ASSERT_NE(e, nullptr);
  effects::EffectSeries s;
  s.time_s = {0.0, 100.0, 200.0};
  s.temp_c = {-2.0, 0.5, 30.0};
  EXPECT_EQ(effects::regressor_values(*e, s, 0.0), (std::vector<double>{16.0, 0.0625, 810000.0}));
  EXPECT_EQ(e->temperature_power, 4);
  EXPECT_TRUE(e->hidden());
}

// 5e-9 °/h/°C⁴ is 0.035 °/h at the cycle's 51.5 °C: a curvature the paper's
// quadratic cannot follow. (Over the cycle's −5.6..51.5 °C, T^3 and T^4 are
// nearly proportional; diagnose says so beside naming T^4 first.)
TEST(TemperatureFourth, WorksEndToEnd) {
  testing::expect_round_trip({.scenario = "cycle", .term = "T^4", .coefficient = 5e-9});
}

}  // namespace
}  // namespace gyrotherm
