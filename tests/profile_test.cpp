#include "sim/profile.h"

#include <gtest/gtest.h>

namespace gyrotherm::sim {
namespace {

Segment hold(double t, double s) { return {SegmentKind::hold, t, 0.0, s, 0}; }
Segment ramp(double t, double r) { return {SegmentKind::ramp, t, r, 0.0, 0}; }
Segment free_drift(double s) { return {SegmentKind::free, 0.0, 0.0, s, 0}; }

TEST(Profile, RampDurationsFollowFromTheRate) {
  const Profile p(20.0, {hold(20.0, 7200.0), ramp(60.0, 5.0), hold(60.0, 7200.0),
                         ramp(-40.0, 5.0)});
  EXPECT_DOUBLE_EQ(p.segment_end_s(1), 7200.0 + 8.0 * 60.0);       // 40 °C at 5 °C/min
  EXPECT_DOUBLE_EQ(p.duration_s(), 7200.0 + 480.0 + 7200.0 + 1200.0);
}

TEST(Profile, SetPointIsPiecewiseLinear) {
  const Profile p(20.0, {hold(20.0, 100.0), ramp(60.0, 6.0), hold(60.0, 100.0)});
  EXPECT_DOUBLE_EQ(p.at(50.0).temp_c, 20.0);
  EXPECT_DOUBLE_EQ(p.at(50.0).rate_c_per_s, 0.0);
  // Ramp: 40 °C at 0.1 °C/s, from t = 100 to 500.
  EXPECT_DOUBLE_EQ(p.at(300.0).temp_c, 40.0);
  EXPECT_DOUBLE_EQ(p.at(300.0).rate_c_per_s, 0.1);
  EXPECT_DOUBLE_EQ(p.at(500.0).temp_c, 60.0);
  EXPECT_DOUBLE_EQ(p.at(550.0).temp_c, 60.0);
  // Past the end the last segment continues.
  EXPECT_DOUBLE_EQ(p.at(1e6).temp_c, 60.0);
}

TEST(Profile, DownRampHasNegativeRate) {
  const Profile p(60.0, {ramp(-40.0, 5.0)});
  EXPECT_NEAR(p.at(600.0).temp_c, 10.0, 1e-12);
  EXPECT_NEAR(p.at(600.0).rate_c_per_s, -5.0 / 60.0, 1e-15);
}

TEST(Profile, FreeSwitchesTheChamberOffAndKeepsTheLastSetPoint) {
  const Profile p(15.0, {hold(25.0, 100.0), free_drift(100.0), ramp(35.0, 1.0)});
  EXPECT_TRUE(p.at(50.0).chamber_on);
  EXPECT_FALSE(p.at(150.0).chamber_on);
  // The ramp after the free drift starts from the last set point (25 °C).
  EXPECT_DOUBLE_EQ(p.segment_start_c(2), 25.0);
  EXPECT_DOUBLE_EQ(p.segment_end_s(2), 200.0 + 600.0);
  EXPECT_TRUE(p.at(300.0).chamber_on);
}

TEST(Profile, TimeOnABreakpointBelongsToTheNextSegment) {
  const Profile p(20.0, {hold(20.0, 100.0), hold(30.0, 100.0)});
  EXPECT_EQ(p.segment_at(99.999), 0u);
  EXPECT_EQ(p.segment_at(100.0), 1u);
  EXPECT_DOUBLE_EQ(p.at(100.0).temp_c, 30.0);
}

}  // namespace
}  // namespace gyrotherm::sim
