// The other sensors of an autopilot log (fit/data/autopilot_log.h with
// fit/data/sensor_kind.h): a ULog's sensor_accel, sensor_baro and sensor_mag
// and a DataFlash log's IMU accelerometers and BARO barometers are read with
// the values written, in the unit the format states (a ULog's pressure in Pa
// or mbar by its PX4 version, or by its values without one); `fit --sensor`
// recovers a known thermal slope from each, whatever unit the log holds; a
// DataFlash magnetometer (no temperature) and a sensor the log lacks are
// refused; the real PX4 logs give their barometers in mbar (v1.11) and Pa
// (v1.16).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "autopilot_log_samples.h"
#include "autopilot_log_writer.h"
#include "cli_runner.h"
#include "expect_input_error.h"
#include "fit/data/autopilot_log.h"

namespace gyrotherm::fit {
namespace {

using testing::CliResult;
using testing::DataFlashWriter;
using testing::expect_input_error;
using testing::expect_refused;
using testing::Packer;
using testing::run_cli;
using testing::ScratchDir;
using testing::ULogWriter;

// 1 Hz for an hour over a 0 → 36 °C ramp: sample k's temperature, and a
// bias of `at_zero` + `slope`·T with a small deterministic wobble (an exact
// line would leave no residual to estimate noise from).
constexpr int kSamples = 3600;
double ramp_c(int k) { return 36.0 * k / kSamples; }
double biased(double at_zero, double slope, int k) {
  return at_zero + slope * ramp_c(k) + 1e-3 * std::abs(at_zero + 1.0) * std::sin(0.7 * k);
}
std::uint64_t stamp_us(int k) { return 5'000'000 + 1'000'000 * static_cast<std::uint64_t>(k); }

// The accelerometer's truth (m/s²), the barometer's (Pa) and the magnetometer's (gauss).
constexpr double kAccelX0 = 0.3, kAccelSlope = 0.002, kPressure0 = 101325.0, kPressureSlope = 3.0;
constexpr double kMag0 = 0.2, kMagSlope = 5e-4;

// One ULog holding a gyro, an accelerometer, a barometer and a magnetometer
// (PX4 v1.14's layouts), the pressure in Pa or, `millibars`, in mbar;
// `version` the ver_sw_release to write (0: none).
ULogWriter imu_ulog(bool millibars, std::uint32_t version, double pressure_scale = 1.0) {
  ULogWriter w;
  if (version != 0) w.info("uint32_t ver_sw_release", Packer().put(version).bytes());
  w.format("sensor_gyro:uint64_t timestamp;uint32_t device_id;float x;float y;float z;float temperature;");
  w.format("sensor_accel:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
           "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;uint8_t[4] _padding0;");
  w.format("sensor_baro:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float pressure;"
           "float temperature;uint32_t error_count;");
  w.format("sensor_mag:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
           "float temperature;uint32_t error_count;");
  w.subscribe(0, 1, "sensor_gyro").subscribe(0, 2, "sensor_accel").subscribe(0, 3, "sensor_baro");
  w.subscribe(0, 4, "sensor_mag");
  for (int k = 0; k < kSamples; ++k) {
    const auto t = static_cast<float>(ramp_c(k));
    w.data(1, Packer().put(stamp_us(k)).put<std::uint32_t>(1).put(0.001f).put(0.0f).put(0.0f).put(t));
    w.data(2, Packer().put(stamp_us(k)).put(stamp_us(k)).put<std::uint32_t>(2)
                  .put(static_cast<float>(biased(kAccelX0, kAccelSlope, k))).put(0.1f).put(-9.8f).put(t)
                  .put<std::uint32_t>(0).zeros(3).put<std::uint8_t>(1));
    const double pa = pressure_scale * biased(kPressure0, kPressureSlope, k);
    w.data(3, Packer().put(stamp_us(k)).put(stamp_us(k)).put<std::uint32_t>(3)
                  .put(static_cast<float>(millibars ? pa / 100.0 : pa)).put(t).put<std::uint32_t>(0));
    w.data(4, Packer().put(stamp_us(k)).put(stamp_us(k)).put<std::uint32_t>(4)
                  .put(static_cast<float>(biased(kMag0, kMagSlope, k))).put(0.0f).put(0.4f).put(t)
                  .put<std::uint32_t>(0));
  }
  return w;
}

// ver_sw_release 0xAABBCCTT: v1.14.0 and v1.11.2 releases, and v0.0 (a build without tags).
constexpr std::uint32_t kV1_14 = 0x010E00FF, kV1_11 = 0x010B0200, kV0 = 0x00000000;

nlohmann::json fitted_t(const ScratchDir& dir, const std::string& args) {
  const CliResult r = run_cli(dir, "fit " + args + " --model T --json");
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

double slope_of(const nlohmann::json& j) {
  return j.contains("coefficients") ? j["coefficients"]["T"].get<double>() : NAN;
}

TEST(LogSensors, AULogsAccelerometerBarometerAndMagnetometerAreReadAsWritten) {
  ScratchDir dir;
  imu_ulog(false, kV1_14).save(dir / "v14.ulg");
  std::vector<testing::LogSample> got;
  const auto sink = [&](double t, double c, double x, double y, double z) { got.push_back({t, c, x, y, z}); };
  const LogContents accel = read_ulog(dir / "v14.ulg", 0, sink, sensor_kind("accel"));
  ASSERT_EQ(got.size(), static_cast<std::size_t>(kSamples));
  EXPECT_EQ(accel.unit, "mps2");
  EXPECT_EQ(accel.sensors.at(0).message, "sensor_accel");
  EXPECT_EQ(accel.sensors.at(0).device_id, 2u);
  EXPECT_EQ(got[10].x, static_cast<float>(biased(kAccelX0, kAccelSlope, 10)));
  EXPECT_EQ(got[10].z, -9.8f);
  EXPECT_EQ(got[10].temp_c, static_cast<float>(ramp_c(10)));
  got.clear();
  const LogContents baro = read_ulog(dir / "v14.ulg", 0, sink, sensor_kind("baro"));
  ASSERT_EQ(got.size(), static_cast<std::size_t>(kSamples));
  EXPECT_EQ(baro.unit, "Pa");
  EXPECT_NE(baro.unit_from.find("v1.14"), std::string::npos) << baro.unit_from;
  EXPECT_EQ(got[7].x, static_cast<float>(biased(kPressure0, kPressureSlope, 7)));
  EXPECT_TRUE(std::isnan(got[7].y) && std::isnan(got[7].z));
  EXPECT_EQ(read_ulog(dir / "v14.ulg", -1, {}, sensor_kind("mag")).unit, "gauss");
  EXPECT_EQ(read_ulog(dir / "v14.ulg", -1, {}, sensor_kind("gyro")).sensors.at(0).message, "sensor_gyro");
}

TEST(LogSensors, AULogsPressureUnitComesFromItsVersionOrElseItsValues) {
  ScratchDir dir;
  const auto unit = [&](bool millibars, std::uint32_t version) {
    imu_ulog(millibars, version).save(dir / "b.ulg");
    const LogContents c = read_ulog(dir / "b.ulg", -1, {}, sensor_kind("baro"));
    EXPECT_FALSE(c.unit_from.empty());
    return c.unit;
  };
  EXPECT_EQ(unit(true, kV1_11), "mbar");
  EXPECT_EQ(unit(false, kV1_14), "Pa");
  EXPECT_EQ(unit(true, 0), "mbar");  // no version message at all
  EXPECT_EQ(unit(false, 0), "Pa");
  // Values no weather gives in mbar are Pa whatever the version says (a
  // development build of v1.11's numbering, a build without tags: v0.0).
  EXPECT_EQ(unit(false, kV1_11), "Pa");
  EXPECT_EQ(unit(true, kV0), "mbar");
  EXPECT_EQ(unit(false, kV0), "Pa");
  // A vacuum (10 mbar, or 1000 Pa?) without a usable version: not told.
  imu_ulog(true, kV0, 0.01).save(dir / "vacuum.ulg");
  const LogContents vacuum = read_ulog(dir / "vacuum.ulg", -1, {}, sensor_kind("baro"));
  EXPECT_EQ(vacuum.unit, "");
  EXPECT_NE(vacuum.unit_from.find("fits a vacuum in Pa as well as mbar"), std::string::npos) << vacuum.unit_from;
  expect_refused(dir, "fit vacuum.ulg --sensor baro --model T", "give --gyro-unit Pa or --gyro-unit mbar");
  EXPECT_NEAR(slope_of(fitted_t(dir, "vacuum.ulg --sensor baro --gyro-unit mbar")), 0.01 * kPressureSlope, 3e-3);
  // A malformed information message leaves the version unknown; a gyro never reads it.
  ULogWriter odd;
  odd.message('I', std::string("\x30short", 6)).format("sensor_gyro:uint64_t timestamp;float x;float y;float z;float temperature;");
  odd.subscribe(0, 1, "sensor_gyro").data(1, Packer().put(stamp_us(0)).put(0.f).put(0.f).put(0.f).put(20.f));
  odd.save(dir / "odd.ulg");
  EXPECT_EQ(read_ulog(dir / "odd.ulg").sensors.at(0).samples, 1u);
}

// `fit --sensor` on each: the truth's slope, in the base unit, whatever the log held.
TEST(LogSensors, FitRecoversEachSensorsSlopeFromAULog) {
  ScratchDir dir;
  imu_ulog(false, kV1_14).save(dir / "pa.ulg");
  imu_ulog(true, kV1_11).save(dir / "mbar.ulg");
  const nlohmann::json accel = fitted_t(dir, "pa.ulg --sensor accel --gyro-col accel_x");
  EXPECT_NEAR(slope_of(accel), kAccelSlope, 1e-4 * kAccelSlope + 2e-6);
  EXPECT_EQ(accel["sensor"], "accel");
  EXPECT_EQ(accel["pipeline"]["columns"]["units"]["gyro"], "mps2");
  const nlohmann::json pa = fitted_t(dir, "pa.ulg --sensor baro");
  const nlohmann::json mbar = fitted_t(dir, "mbar.ulg --sensor baro");
  EXPECT_NEAR(slope_of(pa), kPressureSlope, 0.05);
  EXPECT_NEAR(slope_of(mbar), kPressureSlope, 0.05);  // read in mbar, fitted in Pa
  EXPECT_EQ(mbar["pipeline"]["columns"]["units"]["gyro"], "mbar");
  EXPECT_NEAR(slope_of(fitted_t(dir, "pa.ulg --sensor mag --gyro-col mag_x")), kMagSlope, 2e-6);
  // The text says where the unit came from.
  const CliResult text = run_cli(dir, "fit mbar.ulg --sensor baro --model T");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("PX4 logs pressure in mbar before v1.13"), std::string::npos) << text.out;
  // A stated unit overrides what the reader told from the version; a gyro's stays fixed.
  EXPECT_NEAR(slope_of(fitted_t(dir, "mbar.ulg --sensor baro --gyro-unit Pa")), kPressureSlope / 100.0, 0.001);
  // A fit that read the log in another unit than the reader tells is not applied in either.
  ASSERT_EQ(run_cli(dir, "fit mbar.ulg --sensor baro --gyro-unit Pa --model T -o pa_fit.json").exit_code, 0);
  expect_refused(dir, "compensate mbar.ulg --fit pa_fit.json -o out.csv",
                 "the fit read this barometer's values in Pa, but the log's ver_sw_release is v1.11");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  EXPECT_EQ(run_cli(dir, "compensate mbar.ulg --fit pa_fit.json --gyro-unit Pa -o out.csv").exit_code, 0);
  expect_refused(dir, "fit pa.ulg --sensor accel --gyro-col accel_x --gyro-unit g",
                 "--gyro-unit g: the log is ULog v1, whose units are fixed (time µs, accel mps2");
}

// Copter 4.x IMU (accelerometer beside the gyro) and BARO with its instance
// in I; Copter 3.6's BAR2 for the second barometer.
DataFlashWriter copter_log() {
  DataFlashWriter w;
  w.fmt(140, "IMU", "QBffffffIIfBBHH", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz");
  w.fmt(141, "BARO", "QBffcfIffB", "TimeUS,I,Alt,Press,Temp,CRt,SMS,Offset,GndTemp,Health");
  w.fmt(142, "BAR2", "QffcfIff", "TimeUS,Alt,Press,Temp,CRt,SMS,Offset,GndTemp");
  for (int k = 0; k < kSamples; ++k) {
    const auto t = static_cast<float>(ramp_c(k));
    Packer imu;
    imu.put(stamp_us(k)).put<std::uint8_t>(0).put(0.001f).put(0.0f).put(0.0f);
    imu.put(static_cast<float>(biased(kAccelX0, kAccelSlope, k))).put(0.1f).put(-9.8f);
    imu.put<std::uint32_t>(0).put<std::uint32_t>(0).put(t).put<std::uint8_t>(1).put<std::uint8_t>(1);
    imu.put<std::uint16_t>(1000).put<std::uint16_t>(1000);
    w.message(140, imu.bytes());
    const auto centi = static_cast<std::int16_t>(std::lround(100.0 * ramp_c(k)));
    const auto press = static_cast<float>(biased(kPressure0, kPressureSlope, k));
    w.message(141, Packer().put(stamp_us(k)).put<std::uint8_t>(0).put(12.0f).put(press).put(centi).put(0.0f)
                       .put<std::uint32_t>(0).put(0.0f).put(25.0f).put<std::uint8_t>(1).bytes());
    w.message(142, Packer().put(stamp_us(k)).put(12.0f).put(press + 50.0f).put(centi).put(0.0f)
                       .put<std::uint32_t>(0).put(0.0f).put(25.0f).bytes());
  }
  return w;
}

TEST(LogSensors, ADataFlashLogsAccelerometerAndBarometersAreReadAndFitted) {
  ScratchDir dir;
  copter_log().save(dir / "copter.bin");
  const LogContents baro = read_dataflash(dir / "copter.bin", -1, {}, sensor_kind("baro"));
  EXPECT_EQ(baro.unit, "Pa");
  ASSERT_EQ(baro.sensors.size(), 2u);
  EXPECT_EQ(baro.sensors[0].message, "BARO");
  EXPECT_EQ(baro.sensors[1].message, "BAR2");
  EXPECT_EQ(baro.sensors[1].instance, 1);
  EXPECT_NEAR(baro.sensors[0].temp_max_c, ramp_c(kSamples - 1), 0.006);  // centidegrees
  EXPECT_NEAR(slope_of(fitted_t(dir, "copter.bin --sensor baro")), kPressureSlope, 0.05);
  EXPECT_NEAR(slope_of(fitted_t(dir, "copter.bin --sensor baro --imu 1")), kPressureSlope, 0.05);
  EXPECT_NEAR(slope_of(fitted_t(dir, "copter.bin --sensor accel --gyro-col accel_x")), kAccelSlope, 2e-6);
  // A magnetometer: ArduPilot's MAG message has no temperature.
  expect_refused(dir, "fit copter.bin --sensor mag",
                 "--sensor mag: an ArduPilot log holds no magnetometer temperature");
  // An instance the log lacks, and a log without the sensor.
  expect_refused(dir, "fit copter.bin --sensor baro --imu 2", "the log holds barometer instances 0 and 1");
  DataFlashWriter gyro_only;
  gyro_only.fmt(140, "IMU", "QBfffff", "TimeUS,I,GyrX,GyrY,GyrZ,T,AccX");
  gyro_only.message(140, Packer().put(stamp_us(0)).put<std::uint8_t>(0).put(0.f).put(0.f).put(0.f).put(20.f)
                             .put(0.f).bytes());
  gyro_only.save(dir / "gyro.bin");
  expect_refused(dir, "fit gyro.bin --sensor baro", "no barometer with a temperature to fit against");
  expect_refused(dir, "fit gyro.bin --sensor accel", "FMT of 'IMU'");
}

// The real PX4 logs: v1.11 (CubeOrange) logs its two barometers in mbar,
// v1.16 (FMU-v6C) its one in Pa; both magnetometers' temperatures are NaN.
TEST(LogSensors, TheRealPX4LogsBarometersAreReadInTheirUnits) {
  const std::filesystem::path dir = testing::source_path("../shared/data/real/px4_ulog");
  if (!std::filesystem::exists(dir / "sample_log_small.ulg")) GTEST_SKIP() << "no real PX4 logs at " << dir;
  const LogContents old_baro = read_ulog(dir / "sample_log_small.ulg", -1, {}, sensor_kind("baro"));
  EXPECT_EQ(old_baro.unit, "mbar");
  EXPECT_NE(old_baro.unit_from.find("v1.11"), std::string::npos) << old_baro.unit_from;
  EXPECT_EQ(old_baro.sensors.size(), 2u);
  const LogContents new_baro = read_ulog(dir / "quadrotor_local.ulg", -1, {}, sensor_kind("baro"));
  EXPECT_EQ(new_baro.unit, "Pa");
  EXPECT_NE(new_baro.unit_from.find("v1.16"), std::string::npos) << new_baro.unit_from;
  EXPECT_EQ(new_baro.sensors.size(), 1u);
  EXPECT_EQ(read_ulog(dir / "sample_log_small.ulg", -1, {}, sensor_kind("accel")).sensors.size(), 3u);
  std::vector<double> pressures;
  read_ulog(dir / "sample_log_small.ulg", 0, [&](double, double, double x, double, double) { pressures.push_back(x); },
            sensor_kind("baro"));
  ASSERT_FALSE(pressures.empty());
  EXPECT_GT(pressures.front(), 900.0);  // an atmosphere in mbar
  EXPECT_LT(pressures.front(), 1100.0);
  ScratchDir scratch;
  expect_refused(scratch, "fit " + (dir / "quadrotor_local.ulg").string() + " --sensor mag",
                 "no magnetometer with a temperature to fit against");
}

}  // namespace
}  // namespace gyrotherm::fit
