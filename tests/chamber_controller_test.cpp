#include "sim/chamber_controller.h"

#include <gtest/gtest.h>

namespace gyrotherm::sim {
namespace {

ChamberConfig config() {
  ChamberConfig c;
  c.kp_w_per_k = 100.0;
  c.ti_s = 50.0;
  c.feedforward_j_per_k = 1000.0;
  c.heater_max_w = 500.0;
  c.cooler_max_w = 300.0;
  return c;
}

TEST(ChamberController, UnsaturatedIsProportionalPlusIntegralPlusFeedForward) {
  const ChamberController ctl(config());
  const auto out = ctl.evaluate(21.0, 0.1, 20.0, 50.0, true);
  EXPECT_DOUBLE_EQ(out.power_w, 100.0 * 1.0 + 50.0 + 1000.0 * 0.1);
  EXPECT_DOUBLE_EQ(out.integral_rate_w_per_s, 100.0 * 1.0 / 50.0);
}

TEST(ChamberController, PowerIsLimitedAndTheIntegralBleedsWhileSaturated) {
  const ChamberController ctl(config());
  // Demand 100·10 + 0 = 1000 W > 500 W heater.
  const auto heat = ctl.evaluate(30.0, 0.0, 20.0, 0.0, true);
  EXPECT_DOUBLE_EQ(heat.power_w, 500.0);
  // Back-calculation: (Kp e + (u − v)) / Ti = (1000 − 500) / 50.
  EXPECT_DOUBLE_EQ(heat.integral_rate_w_per_s, (1000.0 + (500.0 - 1000.0)) / 50.0);
  const auto cool = ctl.evaluate(10.0, 0.0, 20.0, 0.0, true);
  EXPECT_DOUBLE_EQ(cool.power_w, -300.0);
  // A wound-up integral is pulled back towards the limit, not further out.
  const auto wound = ctl.evaluate(20.0, 0.0, 20.0, 5000.0, true);
  EXPECT_DOUBLE_EQ(wound.power_w, 500.0);
  EXPECT_LT(wound.integral_rate_w_per_s, 0.0);
}

TEST(ChamberController, OffMeansNoPowerAndAFrozenIntegral) {
  const ChamberController ctl(config());
  const auto out = ctl.evaluate(60.0, 0.0, 20.0, 123.0, false);
  EXPECT_EQ(out.power_w, 0.0);
  EXPECT_EQ(out.integral_rate_w_per_s, 0.0);
}

}  // namespace
}  // namespace gyrotherm::sim
