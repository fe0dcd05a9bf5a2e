// Column roles by name and by values (fit/data/column_role.h): the spellings
// loggers use for other sensors, statuses and counters, and quantities that
// stay candidates.

#include "fit/data/column_role.h"

#include <gtest/gtest.h>

#include <vector>

namespace gyrotherm::fit {
namespace {

TEST(ColumnRole, WordsAreCutAtSeparatorsCaseChangesAndDigits) {
  EXPECT_EQ(column_words("imu.acc.x"), (std::vector<std::string>{"imu", "acc", "x"}));
  EXPECT_EQ(column_words("IMU.AccX"), (std::vector<std::string>{"imu", "acc", "x"}));
  EXPECT_EQ(column_words("accel_x_mps2"), (std::vector<std::string>{"accel", "x", "mps", "2"}));
  EXPECT_EQ(column_words("gyro[1]"), (std::vector<std::string>{"gyro", "1"}));
  EXPECT_EQ(column_words("m1z"), (std::vector<std::string>{"m", "1", "z"}));
}

TEST(ColumnRole, OtherMotionSensorsWhateverTheirSpelling) {
  for (const char* name : {"imu.acc.x", "IMU.AccX", "accel_x_mps2", "gyro[1]", "imu.gyro.y", "GyrX", "xgyro", "zmag",
                           "gx", "ay", "m1z", "wz", "gy_dph", "gyroy rad/s", "ax [m/s^2]", "field_uT", "mag1x [T]",
                           "omega_z"})
    EXPECT_EQ(role_by_name(name), ColumnRole::motion_sensor) << name;
}

TEST(ColumnRole, TheNamesDiagnoseKnewBeforeStillHoldTheirRoles) {
  for (const char* name : {"gy_dph", "gyroy rad/s", "GyrX", "accel_y", "mag1x [T]", "ax", "m1z", "wz", "g2x",
                           "xgyro", "zacc", "AccX", "omega_z", "rate_dps"})
    EXPECT_EQ(role_by_name(name), ColumnRole::motion_sensor) << name;
  for (const char* name : {"supply_v", "case_c", "chamber_c", "temp2_c", "gate_v", "volt", "humidity",
                           "pressure_pa", "heater_w", "board_temp"})
    EXPECT_EQ(role_by_name(name), ColumnRole::cause) << name;
}

TEST(ColumnRole, StatusesAndCountersByName) {
  EXPECT_EQ(role_by_name("imu.status"), ColumnRole::status);
  EXPECT_EQ(role_by_name("SensorFlags"), ColumnRole::status);
  EXPECT_EQ(role_by_name("gps_fix_mode"), ColumnRole::status);
  EXPECT_EQ(role_by_name("packet_count"), ColumnRole::counter);
  EXPECT_EQ(role_by_name("seq"), ColumnRole::counter);
}

TEST(ColumnRole, CausesStayCandidates) {
  for (const char* name : {"case_c", "chamber_c", "supply_v", "imu.temp", "Vbat", "pressure_pa", "heater_pwm"})
    EXPECT_EQ(role_by_name(name), ColumnRole::cause) << name;
}

TEST(ColumnRole, ByValuesFlagsCountersAndConstants) {
  EXPECT_EQ(column_role("x1", std::vector<double>{3, 3, 3, 3}), ColumnRole::constant);
  EXPECT_EQ(column_role("x1", std::vector<double>{0, 1, 1, 0, 2, 0}), ColumnRole::status);
  EXPECT_EQ(column_role("x1", std::vector<double>{10, 12, 14, 16, 18}), ColumnRole::counter);
  EXPECT_EQ(column_role("x1", std::vector<double>{28.1, 28.3, 27.9, 28.0}), ColumnRole::cause);
  EXPECT_EQ(column_role("x1", std::vector<double>{1, 2, 4, 3, 5}), ColumnRole::cause) << "integers that vary freely";
  EXPECT_EQ(column_role("imu.acc.z", std::vector<double>{9.7, 9.8}), ColumnRole::motion_sensor) << "the name first";
}

}  // namespace
}  // namespace gyrotherm::fit
