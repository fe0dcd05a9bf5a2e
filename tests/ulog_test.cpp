// PX4 ULog reader (fit/data/ulog.cpp): logs written here from the spec
// (tests/autopilot_log_writer.h) in sensor_gyro's current and older layouts
// give back exactly the values written; bad files stop with the byte offset
// and what was expected; the real PX4 logs in ../shared/data/real/px4_ulog
// give the instances, counts and temperatures their README states.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "autopilot_log_samples.h"
#include "autopilot_log_writer.h"
#include "cli_runner.h"
#include "expect_input_error.h"
#include "fit/data/autopilot_log.h"

namespace gyrotherm::fit {
namespace {

using testing::expect_input_error;
using testing::Packer;
using testing::ScratchDir;
using testing::ULogWriter;

using Sample = testing::LogSample;

// The values of instance i's sample k, as the firmware holds them (floats).
std::uint64_t time_us(int i, int k) { return 2'000'000 + 250'000 * static_cast<std::uint64_t>(k) + i; }
float rate_x(int i, int k) { return 0.001f * static_cast<float>(k + 1) + static_cast<float>(i); }
float rate_y(int, int k) { return -0.5f * static_cast<float>(k) - 0.0625f; }
float rate_z(int i, int) { return 0.25f + 0.1f * static_cast<float>(i); }
float temp(int i, int k, bool nan) { return nan ? NAN : 30.0f + 0.5f * static_cast<float>(k) + static_cast<float>(i); }

Sample expected(int i, int k, bool nan, bool has_temp = true) {
  return {static_cast<double>(time_us(i, k)) / 1e6, has_temp ? static_cast<double>(temp(i, k, nan)) : NAN, rate_x(i, k),
          rate_y(i, k), rate_z(i, k)};
}

std::vector<Sample> read_samples(const std::filesystem::path& file, int instance, LogContents* contents = nullptr) {
  return testing::read_samples(read_ulog, file, instance, contents);
}

// sensor_gyro as PX4 v1.14 logs it: device_id third, a trailing _padding0
// that the data messages leave out.
constexpr const char* kCurrentFormat =
    "sensor_gyro:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
    "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;uint8_t[4] _padding0;";
Packer current_fields(int i, int k, bool nan, std::uint32_t device) {
  Packer p;
  p.put(time_us(i, k)).put(time_us(i, k) - 120).put(device).put(rate_x(i, k)).put(rate_y(i, k)).put(rate_z(i, k));
  p.put(temp(i, k, nan)).put<std::uint32_t>(0).zeros(3).put<std::uint8_t>(4);
  return p;
}

// Three instances subscribed out of order (2, 0, 1), instance 0's
// temperature NaN throughout, with another topic, information, parameters,
// strings, a sync, a dropout and an unknown message type in between.
ULogWriter current_log(int samples = 4) {
  ULogWriter w;
  w.flag_bits().info("char[3] sys_name", "PX4").parameter("IMU_GYRO_RATEMAX", 400.0f);
  w.format("vehicle_status:uint64_t timestamp;uint8_t arming_state;uint8_t[7] _padding0;").format(kCurrentFormat);
  w.subscribe(2, 0, "sensor_gyro").subscribe(0, 1, "sensor_gyro").subscribe(0, 7, "vehicle_status");
  w.subscribe(1, 2, "sensor_gyro");
  const std::uint32_t device[3] = {2621450, 2621451, 3211274};
  for (int k = 0; k < samples; ++k) {
    for (const int i : {0, 1, 2})
      w.data(static_cast<std::uint16_t>(i == 2 ? 0 : i + 1), current_fields(i, k, i == 0, device[i]));
    w.data(7, Packer().put(time_us(0, k) + 5).put<std::uint8_t>(2));
    if (k == 1) w.logging("[commander] armed", time_us(0, k)).sync().dropout(12).message('Z', "unknown");
  }
  return w;
}

TEST(Ulog, CurrentLayoutGivesTheValuesWrittenForEachInstance) {
  ScratchDir dir;
  const auto file = dir / "current.ulg";
  current_log().save(file);
  EXPECT_EQ(autopilot_log_format(file), "ulog");
  for (const int i : {0, 1, 2}) {
    LogContents c;
    const std::vector<Sample> got = read_samples(file, i, &c);
    ASSERT_EQ(got.size(), 4u);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(got[k], expected(i, k, i == 0)) << "instance " << i << " sample " << k;
    EXPECT_EQ(c.format, "ULog v1");
    EXPECT_FALSE(c.truncated);
  }
  const LogContents c = read_ulog(file);
  ASSERT_EQ(c.sensors.size(), 3u);
  EXPECT_EQ(c.sensors[0].instance, 0);
  EXPECT_EQ(c.sensors[0].device_id, 2621450u);
  EXPECT_EQ(c.sensors[0].samples, 4u);
  EXPECT_EQ(c.sensors[0].samples_with_temperature, 0u);
  EXPECT_TRUE(std::isnan(c.sensors[0].temp_min_c));
  EXPECT_EQ(c.sensors[2].device_id, 3211274u);
  EXPECT_EQ(c.sensors[2].first_time_s, 2.000002);
  EXPECT_EQ(c.sensors[2].last_time_s, 2.750002);
  EXPECT_EQ(c.sensors[2].temp_min_c, 32.0);
  EXPECT_EQ(c.sensors[2].temp_max_c, 33.5);
  EXPECT_EQ(c.default_instance(), 1);  // instance 0 has no temperature
  EXPECT_EQ(c.describe(),
            "ULog v1: sensor_gyro instance 0 (device 2621450): 4 samples, 2.000..2.750 s, temperature NaN "
            "throughout; sensor_gyro instance 1 (device 2621451): 4 samples, 2.000..2.750 s, 31.00..32.50 °C; "
            "sensor_gyro instance 2 (device 3211274): 4 samples, 2.000..2.750 s, 32.00..33.50 °C");
}

// The parameters and the accelerometer `check` reads: 'P' messages (float,
// int32_t) by name, sensor_accel of a multi_id; a sensor_accel format
// without the fields x, y, z is not read, and not refused (the gyros do not need it).
TEST(Ulog, ParametersAndTheAccelerometerAreKeptAndAnOddAccelFormatIsPassedOver) {
  ScratchDir dir;
  ULogWriter w = current_log();
  w.parameter("TC_G_ENABLE", 1.0f);
  w.format("sensor_accel:uint64_t timestamp;float x;float y;float z;");
  w.subscribe(1, 9, "sensor_accel");
  for (int k = 0; k < 3; ++k)
    w.data(9, Packer().put(time_us(0, k)).put(0.0f).put(k == 2 ? 9.0f : 0.0f).put(-9.80665f));  // the last one tilted
  w.save(dir / "accel.ulg");
  const LogContents c = read_ulog(dir / "accel.ulg");
  EXPECT_EQ(c.parameters.at("TC_G_ENABLE"), 1.0);
  EXPECT_EQ(c.parameters.at("IMU_GYRO_RATEMAX"), 400.0);
  ASSERT_NE(c.accel(1), nullptr);
  EXPECT_EQ(c.accel(1)->samples, 3u);
  EXPECT_EQ(c.accel(1)->moving, 1u);
  EXPECT_NEAR(c.accel(1)->largest_tilt_deg, 42.54, 0.01);  // atan(9 / 9.80665)
  ULogWriter odd = current_log();
  odd.format("sensor_accel:uint64_t timestamp;float[3] xyz;");
  odd.subscribe(1, 9, "sensor_accel");
  odd.data(9, Packer().put(time_us(0, 0)).put(0.0f).put(0.0f).put(-9.8f));
  odd.save(dir / "odd.ulg");
  const LogContents o = read_ulog(dir / "odd.ulg");
  EXPECT_EQ(o.accel(1), nullptr);
  EXPECT_EQ(o.sensors.size(), 3u);
}

TEST(Ulog, ASinkWithoutAnInstanceTakesTheDefault) {
  ScratchDir dir;
  const auto file = dir / "current.ulg";
  current_log().save(file);
  const std::vector<Sample> got = read_samples(file, -1);
  ASSERT_EQ(got.size(), 4u);
  EXPECT_EQ(got[3], expected(1, 3, false));
}

// PX4 v1.8-v1.10: integrals and raw counts, device_id after the temperature,
// a trailing _padding0 written in full.
TEST(Ulog, OlderLayoutWithDeviceIdAfterTheTemperature) {
  ScratchDir dir;
  const auto file = dir / "old.ulg";
  ULogWriter w(1);
  w.format(
      "sensor_gyro:uint64_t timestamp;uint64_t integral_dt;uint64_t error_count;float x;float y;float z;"
      "float x_integral;float y_integral;float z_integral;float temperature;float range_rad_s;float scaling;"
      "uint32_t device_id;int16_t x_raw;int16_t y_raw;int16_t z_raw;int16_t temperature_raw;"
      "uint8_t[4] _padding0;");
  w.subscribe(0, 0, "sensor_gyro");
  for (int k = 0; k < 3; ++k) {
    Packer p;
    p.put(time_us(0, k)).put<std::uint64_t>(4000).put<std::uint64_t>(0);
    p.put(rate_x(0, k)).put(rate_y(0, k)).put(rate_z(0, k)).put(1.0f).put(2.0f).put(3.0f);
    p.put(temp(0, k, false)).put(34.9f).put(0.001f).put<std::uint32_t>(1311244);
    p.put<std::int16_t>(-7).put<std::int16_t>(8).put<std::int16_t>(9).put<std::int16_t>(300).zeros(4);
    w.data(0, p);
  }
  w.save(file);
  LogContents c;
  const std::vector<Sample> got = read_samples(file, 0, &c);
  ASSERT_EQ(got.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(got[k], expected(0, k, false));
  ASSERT_EQ(c.sensors.size(), 1u);
  EXPECT_EQ(c.sensors[0].device_id, 1311244u);
  EXPECT_EQ(c.default_instance(), 0);
}

// No device_id and no temperature; a nested type defined after its use and a
// _padding field in the middle (both allowed by the spec); a future version.
TEST(Ulog, NestedTypePaddingAndNoDeviceId) {
  ScratchDir dir;
  const auto file = dir / "nested.ulg";
  ULogWriter w(2);
  w.format("sensor_gyro:uint64_t timestamp;gyro_raw raw;uint8_t[3] _padding0;float x;float y;float z;");
  w.format("gyro_raw:int16_t[3] v;uint8_t flags;");
  w.subscribe(3, 4, "sensor_gyro");
  for (int k = 0; k < 2; ++k) {
    Packer p;
    p.put(time_us(3, k)).put<std::int16_t>(1).put<std::int16_t>(2).put<std::int16_t>(3).put<std::uint8_t>(0);
    p.zeros(3).put(rate_x(3, k)).put(rate_y(3, k)).put(rate_z(3, k));
    w.data(4, p);
  }
  w.save(file);
  LogContents c;
  const std::vector<Sample> got = read_samples(file, 3, &c);
  ASSERT_EQ(got.size(), 2u);
  for (int k = 0; k < 2; ++k) EXPECT_EQ(got[k], expected(3, k, false, false));
  EXPECT_EQ(c.format, "ULog v2");
  ASSERT_EQ(c.sensors.size(), 1u);
  EXPECT_EQ(c.sensors[0].device_id, 0u);
  EXPECT_EQ(c.sensors[0].samples_with_temperature, 0u);
  EXPECT_EQ(c.default_instance(), -1);
  EXPECT_EQ(c.describe(), "ULog v2: sensor_gyro instance 3: 2 samples, 2.000..2.250 s, temperature NaN throughout");
  expect_input_error([&] { read_samples(file, -1); }, {"nested.ulg", "none is chosen by default"});
}

// DATA_APPENDED: the message cut at the appended offset is dropped, and the
// appended messages are read as data.
TEST(Ulog, AppendedDataAfterACutMessageIsRead) {
  ScratchDir dir;
  const auto file = dir / "appended.ulg";
  ULogWriter w;
  w.flag_bits(1, 0);
  w.format(kCurrentFormat).subscribe(0, 0, "sensor_gyro");
  for (int k = 0; k < 2; ++k) w.data(0, current_fields(0, k, false, 1));
  ULogWriter cut;
  cut.data(0, current_fields(0, 9, false, 1));
  w.raw(cut.bytes().substr(16, 20));  // a message cut short by a crash
  const std::uint64_t appended = w.size();
  for (int k = 2; k < 4; ++k) w.data(0, current_fields(0, k, false, 1));
  std::string bytes = w.bytes();
  const std::size_t at = 16 + 3 + 16;  // appended_offsets[0] in the flag bits
  for (int b = 0; b < 8; ++b) bytes[at + b] = static_cast<char>((appended >> (8 * b)) & 0xff);
  testing::write_bytes(file, bytes);
  LogContents c;
  const std::vector<Sample> got = read_samples(file, 0, &c);
  ASSERT_EQ(got.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(got[k], expected(0, k, false));
  EXPECT_FALSE(c.truncated);
}

TEST(Ulog, ABlockBoundaryInsideMessagesChangesNothing) {
  ScratchDir dir;
  const auto file = dir / "large.ulg";
  ULogWriter w;
  w.format(kCurrentFormat).subscribe(0, 0, "sensor_gyro");
  const int n = 30000;  // 1.4 MB: messages straddle the 1 MiB block
  for (int k = 0; k < n; ++k) w.data(0, current_fields(0, k, false, 1));
  w.save(file);
  testing::expect_every_sample(read_ulog, file, 0, n, [](int k) { return expected(0, k, false); });
}

TEST(Ulog, AMessageRunningPastTheEndIsATruncationNotAnError) {
  ScratchDir dir;
  const auto file = dir / "cut.ulg";
  ULogWriter w = current_log(3);
  const std::uint64_t last = w.size();
  w.data(1, current_fields(0, 3, false, 2621450));
  testing::write_bytes(file, w.bytes().substr(0, w.size() - 5));
  testing::expect_truncated_at(read_ulog, file, 0, last, 3);
  // A header cut after its size byte.
  testing::write_bytes(file, w.bytes().substr(0, last + 1));
  EXPECT_TRUE(read_ulog(file).truncated);
}

TEST(Ulog, NotAULogFile) {
  ScratchDir dir;
  const auto file = dir / "data.csv";
  testing::write_bytes(file, "time_s,temp_c,gyro_dph\n0,20,1\n");
  EXPECT_EQ(autopilot_log_format(file), "");
  expect_input_error([&] { read_ulog(file); },
                     {"data.csv: byte 0: not a ULog file", "'ULog' 01 12 35", "found 74 69 6d 65 5f 73 2c"});
  testing::write_bytes(file, "");
  expect_input_error([&] { read_ulog(file); }, {"not a ULog file", "an empty file"});
  expect_input_error([&] { read_ulog(dir / "absent.ulg"); }, {"absent.ulg", "cannot open"});
}

TEST(Ulog, TruncatedHeader) {
  ScratchDir dir;
  const auto file = dir / "short.ulg";
  testing::write_bytes(file, ULogWriter().bytes().substr(0, 11));
  expect_input_error([&] { read_ulog(file); },
                     {"short.ulg: byte 0", "header is cut short", "holds 11 bytes", "needs 16"});
}

TEST(Ulog, DataForAnUnknownMsgId) {
  ScratchDir dir;
  const auto file = dir / "orphan.ulg";
  ULogWriter w;
  w.format(kCurrentFormat).subscribe(0, 0, "sensor_gyro").data(0, current_fields(0, 0, false, 1));
  const std::size_t at = w.size();
  w.data(9, current_fields(0, 1, false, 1));
  testing::expect_refused(read_ulog, file, w,
                          {"orphan.ulg: byte " + std::to_string(at), "msg_id 9", "no subscription ('A')"});
}

TEST(Ulog, AFormatWithAnUnknownType) {
  ScratchDir dir;
  const auto file = dir / "type.ulg";
  ULogWriter w;
  w.flag_bits();
  const std::size_t at = w.size();
  w.format("sensor_gyro:uint64_t timestamp;flaot x;float y;float z;").subscribe(0, 0, "sensor_gyro");
  testing::expect_refused(read_ulog, file, w,
                          {"type.ulg: byte " + std::to_string(at), "format 'sensor_gyro'", "unknown type 'flaot'",
                           "uint64_t", "a format the file defines"});
}

TEST(Ulog, MalformedFormatsAndSubscriptions) {
  ScratchDir dir;
  const auto file = dir / "bad.ulg";
  const auto refused = [&](const ULogWriter& w, const std::vector<std::string>& words) {
    testing::expect_refused(read_ulog, file, w, words);
  };
  refused(std::move(ULogWriter().format("sensor_gyro uint64_t timestamp")), {"byte 16", "'name:type field;...'"});
  refused(std::move(ULogWriter().format("sensor_gyro:uint64_t timestamp;float[x] x;")),
          {"field 'float[x] x'", "type[length] name"});
  refused(
      std::move(ULogWriter().format("sensor_gyro:uint64_t timestamp;float y;float z;").subscribe(0, 0, "sensor_gyro")),
      {"no field 'x'", "it has timestamp, y, z"});
  refused(std::move(ULogWriter()
                        .format("sensor_gyro:uint64_t timestamp;float[3] x;float y;float z;")
                        .subscribe(0, 0, "sensor_gyro")),
          {"field 'x' is a 'float[3]', expected a number"});
  refused(std::move(ULogWriter().format("a:uint64_t timestamp;b inner;").format("b:a outer;").subscribe(0, 0, "a")),
          {"nested more than 32 deep"});
  refused(std::move(ULogWriter().subscribe(0, 0, "sensor_gyro")), {"byte 16", "no format definition ('F')"});
  refused(std::move(ULogWriter().flag_bits(0, 0, 0x04)), {"byte 16", "incompatible flag bits", "00 04 00"});
  ULogWriter short_data;
  short_data.format(kCurrentFormat).subscribe(0, 0, "sensor_gyro").data(0, Packer().put<std::uint64_t>(1));
  refused(std::move(short_data), {"sensor_gyro data message (instance 0) holds 8 bytes", "needs 36"});
}

TEST(Ulog, AnInstanceTheFileDoesNotHold) {
  ScratchDir dir;
  ULogWriter empty;
  empty.format(kCurrentFormat);
  testing::expect_gyro_choice(read_ulog, dir / "current.ulg", current_log(), 5, "0, 1 and 2", empty, "ULog v1");
}

// The real logs (PX4/pyulog and Auterion/px4-ulog-rs test fixtures; see their README).
std::filesystem::path real_log(const char* name) {
  return std::filesystem::path(GYROTHERM_SOURCE_DIR "/../shared/data/real/px4_ulog/") / name;
}

TEST(UlogRealLogs, SampleLogSmallHoldsThreeGyros) {
  const auto file = real_log("sample_log_small.ulg");
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "absent: " << file;
  EXPECT_EQ(autopilot_log_format(file), "ulog");
  const LogContents c = read_ulog(file);
  ASSERT_EQ(c.sensors.size(), 3u) << c.describe();
  const double low[3] = {40.03, 28.25, 29.43}, high[3] = {40.36, 28.37, 29.72};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(c.sensors[i].instance, i);
    EXPECT_EQ(c.sensors[i].samples, 6u);
    EXPECT_EQ(c.sensors[i].samples_with_temperature, 6u);
    EXPECT_NEAR(c.sensors[i].temp_min_c, low[i], 0.005);
    EXPECT_NEAR(c.sensors[i].temp_max_c, high[i], 0.005);
    EXPECT_NE(c.sensors[i].device_id, 0u);
  }
  EXPECT_EQ(c.default_instance(), 0);
  EXPECT_FALSE(c.truncated);
  std::vector<Sample> got = read_samples(file, 2);
  ASSERT_EQ(got.size(), 6u);
  for (std::size_t k = 1; k < got.size(); ++k) EXPECT_GT(got[k].time_s, got[k - 1].time_s);
  for (const Sample& s : got) EXPECT_LT(std::abs(s.x) + std::abs(s.y) + std::abs(s.z), 1.0);  // on the ground
}

TEST(UlogRealLogs, QuadrotorLocalDefaultsToTheGyroWithATemperature) {
  const auto file = real_log("quadrotor_local.ulg");
  if (!std::filesystem::exists(file)) GTEST_SKIP() << "absent: " << file;
  const LogContents c = read_ulog(file);
  ASSERT_EQ(c.sensors.size(), 2u) << c.describe();
  EXPECT_EQ(c.sensors[0].samples, 92u);
  EXPECT_EQ(c.sensors[0].samples_with_temperature, 0u);
  EXPECT_EQ(c.sensors[1].samples, 92u);
  EXPECT_EQ(c.sensors[1].samples_with_temperature, 92u);
  EXPECT_NEAR(c.sensors[1].temp_min_c, 23.95, 0.005);
  EXPECT_NEAR(c.sensors[1].temp_max_c, 25.73, 0.005);
  EXPECT_EQ(c.default_instance(), 1);
  EXPECT_NE(c.describe().find("sensor_gyro instance 0"), std::string::npos);
  EXPECT_NE(c.describe().find("temperature NaN throughout"), std::string::npos);
  EXPECT_EQ(read_samples(file, -1).size(), 92u);
}

}  // namespace
}  // namespace gyrotherm::fit
