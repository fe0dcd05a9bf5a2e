// check of another sensor's calibration (studies/check with
// fit/data/sensor_kind.h): the simulated MEMS IMU's accelerometer and
// barometer fitted on one log (seed 40) and exported as PX4's TC_A / TC_B
// and ArduPilot's INS_TCAL1_ACC*, then checked on a second log of the same
// IMU (seed 41): each file is read for its sensor (told by its parameter
// names, or by --sensor), applied by its firmware's rule in the sensor's
// unit, paired with the log's sensor by device id, and takes most of the
// thermal drift off every axis; a fit file of the accelerometer is applied as
// compensate applies it; a file without the sensor asked for is refused
// naming what it holds.

#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace gyrotherm::studies {
namespace {

using testing::CliResult, testing::expect_refused, testing::run_cli, testing::ScratchDir, testing::source_path;

nlohmann::json checked(const ScratchDir& dir, const std::string& args) {
  const CliResult r = run_cli(dir, "check " + args + " --json");
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

// Every axis's drift mostly taken off, and nothing found that blocks a pass.
void expect_calibrated(const nlohmann::json& j, const std::string& sensor, std::size_t axes, double least_ratio) {
  EXPECT_EQ(j["sensor"], sensor) << j.dump().substr(0, 300);
  ASSERT_EQ(j["axes"].size(), axes);
  for (const auto& a : j["axes"]) EXPECT_GT(a["ratio"].get<double>(), least_ratio) << sensor << " " << a["axis"];
  for (const auto& f : j["findings"])
    for (const char* blocking : {"moving", "device_mismatch", "made_worse", "already_enabled", "fitted_log"})
      EXPECT_NE(f["issue"], blocking) << f["text"];
}

TEST(CheckSensor, AnAccelerometersAndABarometersCalibrationsHoldOnASecondLog) {
  ScratchDir dir;
  const std::string imu = source_path("scenarios/imu.toml");
  for (const char* args : {" -o one.ulg", " --seed 41 -o two.ulg", " -o one.bin", " --seed 41 -o two.bin"})
    ASSERT_EQ(run_cli(dir, "simulate " + imu + args).exit_code, 0) << args;
  const std::string cubic = " --model 'T + T^2 + T^3'";
  ASSERT_EQ(run_cli(dir, "fit one.ulg --sensor accel" + cubic + " -o accel.json").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "fit one.ulg --sensor baro" + cubic + " -o baro.json").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "fit one.bin --sensor accel" + cubic + " -o accel_ap.json").exit_code, 0);
  // The simulated ULog's device ids (sim/ulog_record.cpp): the accelerometer's and the barometer's.
  ASSERT_EQ(run_cli(dir, "export accel.json --format px4 --device-id 1310996 -o accel.params").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "export baro.json --format px4 --device-id 6620172 -o baro.params").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "export accel_ap.json --format ardupilot -o accel.parm").exit_code, 0);

  // Told by the parameter names (TC_A, TC_B) or by --sensor.
  const nlohmann::json a = checked(dir, "two.ulg --params accel.params --max-residual 0.004 --residual-unit mps2");
  expect_calibrated(a, "accel", 3, 10.0);
  EXPECT_EQ(a["unit"], "m/s²");
  EXPECT_EQ(a["device_id"], 1310996);
  EXPECT_EQ(a["passed"], true) << a["findings"].dump();
  // The second log covers the calibrated range: nothing lies outside it beyond the soaks' noise.
  for (const auto& f : a["findings"]) EXPECT_NE(f["issue"], "outside_range") << f["text"];
  const nlohmann::json b = checked(dir, "two.ulg --params baro.params --sensor baro");
  expect_calibrated(b, "baro", 1, 10.0);
  EXPECT_EQ(b["axes"][0]["axis"], "pressure");
  const nlohmann::json ap = checked(dir, "two.bin --params accel.parm");
  expect_calibrated(ap, "accel", 3, 10.0);
  // ArduPilot's accelerometer keeps gravity: its offsets are its calibration's, not the log's start.
  EXPECT_LT(ap["axes"][2]["offset_dph"].get<double>(), -9.0);
  EXPECT_NEAR(ap["axes"][2]["offset_dph"].get<double>(), a["axes"][2]["offset_dph"].get<double>(), 0.05);
  // A fit file is applied as compensate applies it.
  expect_calibrated(checked(dir, "two.ulg --params accel.json"), "accel", 3, 10.0);

  const CliResult text = run_cli(dir, "check two.ulg --params accel.params");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("raw m/s²"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("accelerometer instance 0, device 1310996"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("°/h"), std::string::npos) << text.out;

  // A gyro's unit for an accelerometer's limit; a file without the sensor asked for, and a fit of another sensor.
  expect_refused(dir, "check two.ulg --params accel.params --max-residual 1 --residual-unit dph",
                 "--residual-unit dph");
  expect_refused(dir, "check two.ulg --params accel.params --sensor baro",
                 "accel.params: it holds no barometer thermal parameters (it holds the accelerometer's (--sensor accel))");
  expect_refused(dir, "check two.ulg --params accel.params --sensor gyro", "it holds no gyro thermal parameters");
  expect_refused(dir, "check two.ulg --params baro.json --sensor accel",
                 "--sensor accel: baro.json is the barometer's fit (--sensor baro)");
}

}  // namespace
}  // namespace gyrotherm::studies
