// T^4 (sim/effects/temperature_fourth.cpp): its regressor by hand, and the
// effect end to end: simulated hidden on the cycle, fitted, diagnosed,
// compensated with, exported in C and refused by the cubic firmwares.

#include <gtest/gtest.h>

#include "effect_round_trip.h"

namespace gyrotherm::testing {
namespace {

TEST(TemperatureFourth, IsTheFourthPowerOfT) { expect_regressor_at("T^4", {-2.0, 0.5, 30.0}, {16.0, 0.0625, 810000.0}); }

// 5e-9 °/h/°C⁴ is 0.035 °/h at the cycle's 51.5 °C: a curvature the paper's
// quadratic cannot follow. (Over the cycle's −5.6..51.5 °C, T^3, T^4 and T^5
// are nearly proportional; diagnose says so beside naming one of them first.)
TEST(TemperatureFourth, WorksEndToEnd) { expect_round_trip({.scenario = "cycle", .term = "T^4", .coefficient = 5e-9}); }

}  // namespace
}  // namespace gyrotherm::testing
