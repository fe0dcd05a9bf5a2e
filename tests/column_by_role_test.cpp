// A CSV's measured columns chosen by role (fit/data/column_map.cpp's
// columns_for): with the kind's default column absent, the one column (or
// the three axes x, y, z) whose names say the sensor — as loggers write
// them: GyrX, gyro_x [dps], imu.acc.x, AccX, accel_x_mps2 — is read, each in
// the unit its name states; a model's or a truth's column is not taken for
// a reading; anything ambiguous is refused with the columns listed.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace gyrotherm::fit {
namespace {

using testing::CliResult, testing::expect_refused, testing::run_cli, testing::ScratchDir;

nlohmann::json fitted(const ScratchDir& dir, const std::string& args) {
  const CliResult r = run_cli(dir, "fit " + args + " --model T --json");
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

// Channel `name`'s fit and its slope in the sensor's base unit per °C.
double slope_of(const nlohmann::json& j, const std::string& name) {
  for (const auto& c : j["channels"])
    if (c["channel"] == name) return c["coefficients"]["T"].get<double>();
  ADD_FAILURE() << "no channel " << name << " in " << j.dump().substr(0, 300);
  return 0.0;
}

TEST(ColumnsByRole, AGyrosAndAnAccelerometersAxesAreReadByTheirNamesAndUnits) {
  ScratchDir dir;
  // 2 h, 10 → 40 °C; each column slope·T + N(0, 0.5) in its own unit.
  testing::write_ramp_log(dir / "imu.csv", "gyro_x [dps],gyro_y [dps],gyro_z [dps],AccX [g],AccY [g],AccZ [g]",
                          {1.0, 2.0, -1.0, 0.02, 0.04, -0.02}, 2.0, 10.0, 40.0, 5);
  const double se = 0.5 / std::sqrt(7200.0) / (30.0 / std::sqrt(12.0));  // the slope's standard error, per unit
  const nlohmann::json gyro = fitted(dir, "imu.csv");
  ASSERT_EQ(gyro["channels"].size(), 3u) << gyro.dump().substr(0, 300);
  EXPECT_NEAR(slope_of(gyro, "gyro_y [dps]"), 2.0 * 3600.0, 5.0 * se * 3600.0);  // dps read as °/h
  EXPECT_NEAR(slope_of(gyro, "gyro_z [dps]"), -1.0 * 3600.0, 5.0 * se * 3600.0);
  const nlohmann::json accel = fitted(dir, "imu.csv --sensor accel");
  ASSERT_EQ(accel["channels"].size(), 3u);
  EXPECT_NEAR(slope_of(accel, "AccX [g]"), 0.02 * 9.80665, 5.0 * se * 9.80665);  // g read as m/s²
  EXPECT_NEAR(slope_of(accel, "AccY [g]"), 0.04 * 9.80665, 5.0 * se * 9.80665);
  EXPECT_EQ(accel["channels"][0]["pipeline"]["columns"]["gyro"], "AccX [g]");

  // Loggers' names without a unit: the kind's base unit; one column alone.
  testing::write_ramp_log(dir / "acc.csv", "imu.acc.x,imu.acc.y,imu.acc.z", {0.01, 0.02, 0.03}, 2.0, 10.0, 40.0, 6);
  EXPECT_NEAR(slope_of(fitted(dir, "acc.csv --sensor accel"), "imu.acc.z"), 0.03, 5.0 * se);
  testing::write_ramp_log(dir / "one.csv", "accel_x_mps2", {0.01}, 2.0, 10.0, 40.0, 7);
  const nlohmann::json one = fitted(dir, "one.csv --sensor accel");
  EXPECT_EQ(one["pipeline"]["columns"]["gyro"], "accel_x_mps2");
  EXPECT_NEAR(one["coefficients"]["T"].get<double>(), 0.01, 5.0 * se);

  // Ambiguous: two accelerometer columns with no axes between them; and
  // another kind's columns are never taken for the gyro's.
  testing::write_ramp_log(dir / "two.csv", "acc_a,acc_b", {0.01, 0.02}, 1.0, 10.0, 40.0, 8);
  expect_refused(dir, "fit two.csv --sensor accel", "acc_a, acc_b may be the accelerometer's: give --gyro-col");
  expect_refused(dir, "fit acc.csv", "may be the accelerometer's: to fit them, give --sensor accel");
}

// An accelerometer at rest in g, its names stating no unit: read as m/s²
// its three axes make 1, not gravity's 9.81, and that is cautioned with the
// unit that fits; given --gyro-unit g, nothing is; export stops at it.
TEST(ColumnsByRole, AnAccelerometerInGReadAsMetresPerSecondSquaredIsCautioned) {
  ScratchDir dir;
  testing::write_ramp_log(dir / "g.csv", "AccX,AccY,AccZ", {0.001, -0.001, 0.002}, 2.0, 10.0, 40.0, 9);
  // z holds gravity, -1 g, as a board lying flat reads it.
  ASSERT_EQ(testing::run_shell(dir, "awk -F, -v OFS=, 'NR > 1 { $5 = $5 / 100 - 1; $3 = $3 / 100; $4 = $4 / 100 } "
                                    "{ print }' g.csv | tee flat.csv").exit_code, 0);
  const CliResult r = run_cli(dir, "fit flat.csv --sensor accel --model T -o fit.json --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 3u);
  const nlohmann::json& cautions = j["channels"][2]["data"]["cautions"];
  ASSERT_EQ(cautions.size(), 1u) << cautions.dump();
  EXPECT_NE(cautions[0].get<std::string>().find("are its numbers in g (standard gravities"), std::string::npos)
      << cautions[0];
  expect_refused(dir, "export fit.json --format px4 -o a.params", "--accept-caution");
  // A fact of the three axes together: said once in the text.
  const std::string text = run_cli(dir, "fit flat.csv --sensor accel --model T").out;
  const std::size_t first = text.find("median magnitude");
  EXPECT_NE(first, std::string::npos) << text;
  EXPECT_EQ(text.find("median magnitude", first + 1), std::string::npos) << text;
  const CliResult in_g = run_cli(dir, "fit flat.csv --sensor accel --gyro-unit g --model T --json");
  ASSERT_EQ(in_g.exit_code, 0) << in_g.err;
  EXPECT_TRUE(nlohmann::json::parse(in_g.out)["channels"][2]["data"]["cautions"].empty());
}

TEST(ColumnsByRole, ASimulatedIMUsCSVIsReadBySensorEachAxisMeetingItsTruth) {
  ScratchDir dir;
  ASSERT_EQ(run_cli(dir, "simulate " + testing::source_path("scenarios/imu.toml") + " -o imu.csv").exit_code, 0);
  // accel_x_mps2 .. accel_z_mps2, not their *_true_* columns.
  const CliResult r = run_cli(dir, "fit imu.csv --sensor accel --model 'T + T^2 + T^3' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 3u);
  EXPECT_EQ(j["channels"][2]["channel"], "accel_z_mps2");
  EXPECT_EQ(j["channels"][2]["truth"]["T^3"], 1e-7);  // scenarios/imu_gyro.toml
  const nlohmann::json& i = j["channels"][2]["intervals_95"]["T^3"];
  EXPECT_LE(i[0].get<double>(), 1e-7);
  EXPECT_GE(i[1].get<double>(), 1e-7);
  // The gyro: gyro_dph is there, so it alone (its y and z are the user's to name).
  const CliResult g = run_cli(dir, "fit imu.csv --model T --json");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  EXPECT_FALSE(nlohmann::json::parse(g.out).contains("channels"));
}

}  // namespace
}  // namespace gyrotherm::fit
