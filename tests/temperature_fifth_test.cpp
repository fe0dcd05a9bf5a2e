// T^5 (sim/effects/temperature_fifth.cpp): its regressor by hand (odd, so
// below 0 °C it is negative), and the effect end to end on the cycle.

#include <gtest/gtest.h>

#include "effect_round_trip.h"

namespace gyrotherm::testing {
namespace {

TEST(TemperatureFifth, IsTheFifthPowerOfT) { expect_regressor_at("T^5", {-2.0, 0.5, 30.0}, {-32.0, 0.03125, 24300000.0}); }

// 1e-10 °/h/°C⁵ is 0.037 °/h at the cycle's 51.5 °C.
TEST(TemperatureFifth, WorksEndToEnd) { expect_round_trip({.scenario = "cycle", .term = "T^5", .coefficient = 1e-10}); }

}  // namespace
}  // namespace gyrotherm::testing
