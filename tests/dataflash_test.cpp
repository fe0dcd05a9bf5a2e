// ArduPilot DataFlash reader (fit/data/dataflash.cpp): logs written here from
// the published format (tests/autopilot_log_writer.h) with the IMU message of
// Copter 4.x (instance field I), 3.6 (IMU, IMU2, IMU3), 3.4 (Temp) and 3.2
// (TimeMS) give back exactly the values written; bad files stop with the
// byte offset and what was expected.

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

using testing::DataFlashWriter;
using testing::expect_input_error;
using testing::Packer;
using testing::ScratchDir;

using Sample = testing::LogSample;

std::uint64_t time_us(int i, int k) { return 60'000'000 + 2'500 * static_cast<std::uint64_t>(k) + 10 * i; }
float gyr(int i, int k, int axis) {
  return 0.0078125f * static_cast<float>(k - 2 * axis) + 0.03f * static_cast<float>(i);
}
float temp(int i, int k) { return 45.25f + 0.125f * static_cast<float>(k) - static_cast<float>(i); }

Sample expected(int i, int k, double time_divisor = 1e6, std::uint64_t time = 0) {
  return {static_cast<double>(time != 0 ? time : time_us(i, k)) / time_divisor, temp(i, k), gyr(i, k, 0), gyr(i, k, 1),
          gyr(i, k, 2)};
}

std::vector<Sample> read_samples(const std::filesystem::path& file, int instance, LogContents* contents = nullptr) {
  return testing::read_samples(read_dataflash, file, instance, contents);
}

// Other messages a log holds between the IMU ones.
void other_messages(DataFlashWriter& w) {
  w.fmt(160, "PARM", "QNf", "TimeUS,Name,Value").fmt(161, "MSG", "QZ", "TimeUS,Message");
  w.fmt(162, "GPS", "QBBIHBcLLeffffB", "TimeUS,I,Status,GMS,GWk,NSats,HDop,Lat,Lng,Alt,Spd,GCrs,VZ,Yaw,U");
  w.message(160, Packer().put<std::uint64_t>(1).text("INS_GYRO_FILTER", 16).put(20.0f).bytes());
  w.message(161, Packer().put<std::uint64_t>(2).text("ArduCopter V4.5.7", 64).bytes());
}

// Copter 4.x: one IMU message, the instance in I (uint8).
constexpr const char* kImu4Format = "QBffffffIIfBBHH";
constexpr const char* kImu4Labels = "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz";
Packer imu4(int i, int k, float temperature) {
  Packer p;
  p.put(time_us(i, k)).put(static_cast<std::uint8_t>(i)).put(gyr(i, k, 0)).put(gyr(i, k, 1)).put(gyr(i, k, 2));
  p.put(0.1f).put(-0.2f).put(-9.8f).put<std::uint32_t>(0).put<std::uint32_t>(0).put(temperature);
  p.put<std::uint8_t>(1).put<std::uint8_t>(1).put<std::uint16_t>(1000).put<std::uint16_t>(1000);
  return p;
}
DataFlashWriter copter4(int samples = 5, bool nan_instance0 = true) {
  DataFlashWriter w;
  other_messages(w);
  w.fmt(140, "IMU", kImu4Format, kImu4Labels);
  for (int k = 0; k < samples; ++k) {
    for (const int i : {1, 0}) w.message(140, imu4(i, k, i == 0 && nan_instance0 ? NAN : temp(i, k)).bytes());
    if (k == 2) w.message(161, Packer().put<std::uint64_t>(3).text("EKF3 IMU0 is using GPS", 64).bytes());
  }
  return w;
}

TEST(DataFlash, Copter4ImuWithTheInstanceField) {
  ScratchDir dir;
  const auto file = dir / "copter4.bin";
  copter4().save(file);
  EXPECT_EQ(autopilot_log_format(file), "dataflash");
  for (const int i : {0, 1}) {
    LogContents c;
    const std::vector<Sample> got = read_samples(file, i, &c);
    ASSERT_EQ(got.size(), 5u);
    for (int k = 0; k < 5; ++k) {
      Sample want = expected(i, k);
      if (i == 0) want.temp_c = NAN;
      EXPECT_EQ(got[k], want) << "instance " << i << " sample " << k;
    }
  }
  const LogContents c = read_dataflash(file);
  EXPECT_EQ(c.format, "DataFlash");
  ASSERT_EQ(c.sensors.size(), 2u);
  EXPECT_EQ(c.sensors[0].instance, 0);
  EXPECT_EQ(c.sensors[0].message, "IMU");
  EXPECT_EQ(c.sensors[0].device_id, 0u);
  EXPECT_EQ(c.sensors[1].samples_with_temperature, 5u);
  EXPECT_EQ(c.sensors[1].temp_min_c, 44.25);
  EXPECT_EQ(c.sensors[1].temp_max_c, 44.75);
  EXPECT_EQ(c.sensors[1].first_time_s, 60.00001);
  EXPECT_EQ(c.default_instance(), 1);
  EXPECT_EQ(c.describe(),
            "DataFlash: IMU instance 0: 5 samples, 60.000..60.010 s, temperature NaN throughout; "
            "IMU instance 1: 5 samples, 60.000..60.010 s, 44.25..44.75 °C");
  // A sink without an instance takes the default.
  EXPECT_EQ(read_samples(file, -1).at(4), expected(1, 4));
}

// Copter 3.6: IMU, IMU2, IMU3 without an instance field.
TEST(DataFlash, Copter36ImuImu2Imu3) {
  ScratchDir dir;
  const auto file = dir / "copter36.bin";
  DataFlashWriter w;
  const char* labels = "TimeUS,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz";
  w.fmt(131, "IMU", "QffffffIIfBBHH", labels).fmt(146, "IMU2", "QffffffIIfBBHH", labels);
  w.fmt(147, "IMU3", "QffffffIIfBBHH", labels);
  other_messages(w);
  for (int k = 0; k < 3; ++k)
    for (const int i : {0, 1, 2}) {
      Packer p;
      p.put(time_us(i, k)).put(gyr(i, k, 0)).put(gyr(i, k, 1)).put(gyr(i, k, 2)).put(0.0f).put(0.0f).put(-9.8f);
      p.put<std::uint32_t>(0).put<std::uint32_t>(0).put(temp(i, k)).put<std::uint8_t>(1).put<std::uint8_t>(1);
      p.put<std::uint16_t>(400).put<std::uint16_t>(400);
      w.message(static_cast<std::uint8_t>(i == 0 ? 131 : 145 + i), p.bytes());
    }
  w.save(file);
  for (const int i : {0, 1, 2}) {
    LogContents c;
    const std::vector<Sample> got = read_samples(file, i, &c);
    ASSERT_EQ(got.size(), 3u);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(got[k], expected(i, k));
    ASSERT_EQ(c.sensors.size(), 3u);
    EXPECT_EQ(c.sensors[i].message, i == 0 ? "IMU" : "IMU" + std::to_string(i + 1));
    EXPECT_EQ(c.sensors[i].instance, i);
    EXPECT_EQ(c.default_instance(), 0);
  }
}

// Copter 3.4 names the temperature Temp; Copter 3.2 (and Solo) logs time in ms.
TEST(DataFlash, Copter34TempAndCopter32TimeMs) {
  ScratchDir dir;
  const auto file = dir / "copter34.bin";
  DataFlashWriter w;
  w.fmt(132, "IMU", "QffffffIIfBB", "TimeUS,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,ErrG,ErrA,Temp,GyHlt,AcHlt");
  for (int k = 0; k < 3; ++k) {
    Packer p;
    p.put(time_us(0, k)).put(gyr(0, k, 0)).put(gyr(0, k, 1)).put(gyr(0, k, 2)).put(0.0f).put(0.0f).put(-9.8f);
    p.put<std::uint32_t>(0).put<std::uint32_t>(0).put(temp(0, k)).put<std::uint8_t>(1).put<std::uint8_t>(1);
    w.message(132, p.bytes());
  }
  w.save(file);
  std::vector<Sample> got = read_samples(file, 0);
  ASSERT_EQ(got.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(got[k], expected(0, k));

  DataFlashWriter old;
  old.fmt(135, "IMU2", "IffffffIIf", "TimeMS,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,ErrG,ErrA,Temp");
  for (int k = 0; k < 2; ++k) {
    Packer p;
    p.put(static_cast<std::uint32_t>(123456 + 20 * k)).put(gyr(1, k, 0)).put(gyr(1, k, 1)).put(gyr(1, k, 2));
    p.put(0.0f).put(0.0f).put(-9.8f).put<std::uint32_t>(0).put<std::uint32_t>(0).put(temp(1, k));
    old.message(135, p.bytes());
  }
  old.save(file);
  got = read_samples(file, 1);
  ASSERT_EQ(got.size(), 2u);
  for (int k = 0; k < 2; ++k) EXPECT_EQ(got[k], expected(1, k, 1e3, 123456 + 20 * k));
}

TEST(DataFlash, ABlockBoundaryInsideMessagesChangesNothing) {
  ScratchDir dir;
  const auto file = dir / "large.bin";
  const int n = 30000;  // 1.5 MB: messages straddle the 1 MiB block
  copter4(n, false).save(file);
  testing::expect_every_sample(read_dataflash, file, 0, n, [](int k) { return expected(0, k); });
}

TEST(DataFlash, AMessageRunningPastTheEndIsATruncationNotAnError) {
  ScratchDir dir;
  const auto file = dir / "cut.bin";
  DataFlashWriter w = copter4(3);
  const std::size_t last = w.size();
  w.message(140, imu4(1, 3, temp(1, 3)).bytes());
  for (const std::size_t keep : {w.size() - 7, last + 2, last + 1}) {
    testing::write_bytes(file, w.bytes().substr(0, keep));
    testing::expect_truncated_at(read_dataflash, file, 1, last, 3);
  }
}

TEST(DataFlash, NotADataFlashLog) {
  ScratchDir dir;
  const auto file = dir / "flight.ulg";
  testing::write_bytes(file, testing::ULogWriter().bytes());
  EXPECT_EQ(autopilot_log_format(file), "ulog");
  expect_input_error([&] { read_dataflash(file); },
                     {"flight.ulg: byte 0: not a DataFlash log", "a3 95", "found 55 4c"});
}

TEST(DataFlash, AnUnknownTypeInTheMiddleIsCorrupt) {
  ScratchDir dir;
  const auto file = dir / "corrupt.bin";
  DataFlashWriter w = copter4(2);
  const std::size_t at = w.size();
  w.message(200, std::string(20, 'x'));
  testing::expect_refused(read_dataflash, file, w,
                          {"corrupt.bin: byte " + std::to_string(at), "message type 200 has no FMT", "140 IMU"});
  testing::expect_refused(read_dataflash, file, copter4(2).raw("\x01\x02\x03\x04"),
                          {"byte " + std::to_string(at), "expected a message starting a3 95", "found 01 02"});
}

TEST(DataFlash, FormatsThatCannotBeRead) {
  ScratchDir dir;
  const auto file = dir / "fmt.bin";
  const auto refused = [&](const DataFlashWriter& w, const std::vector<std::string>& words) {
    testing::expect_refused(read_dataflash, file, w, words);
  };
  refused(DataFlashWriter().fmt(140, "IMU", "QBfffX", "TimeUS,I,GyrX,GyrY,GyrZ,W", 40),
          {"byte 89", "FMT of 'IMU'", "unknown format character 'X'"});
  refused(DataFlashWriter().fmt(140, "IMU", "QBfff", "TimeUS,I,GyrX,GyrY,GyrZ", 30),
          {"byte 89", "the format adds up to 24 bytes with the header, the FMT says 30"});
  refused(DataFlashWriter().fmt(140, "IMU", "QBff", "TimeUS,I,GyrX,GyrY"), {"no field 'GyrZ'"});
  refused(DataFlashWriter().fmt(140, "IMU", "QBfff", "TimeUS,I,GyrX,GyrY"), {"4 labels for 5 format characters"});
  refused(DataFlashWriter().fmt(140, "IMU", "QBffN", "TimeUS,I,GyrX,GyrY,GyrZ"),
          {"field 'GyrZ' is of format 'N', text, expected a number"});
  refused(DataFlashWriter().fmt(128, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns", 90),
          {"length 90, expected FMT's own: 89 bytes"});
  DataFlashWriter half_instance;
  half_instance.fmt(140, "IMU", "QffffI", "TimeUS,I,GyrX,GyrY,GyrZ,EG");
  const std::size_t imu_at = half_instance.size();
  half_instance.message(140, Packer().put<std::uint64_t>(1).put(1.5f).put(0.f).put(0.f).put(0.f).put(0u).bytes());
  refused(half_instance, {"byte " + std::to_string(imu_at), "instance I = 1.5, expected a whole number 0..255"});
  // A type this reader cannot size is skipped by its length when it is not an IMU.
  DataFlashWriter fine = copter4(2);
  fine.fmt(150, "NEW", "QX", "TimeUS,Thing", 13)
      .message(150, std::string(10, '\0'))
      .message(140, imu4(1, 2, 1.0f).bytes());
  fine.save(file);
  EXPECT_EQ(read_dataflash(file).sensors.at(1).samples, 3u);
  // A FMT that contradicts itself for a message the reader does not need (a
  // Copter 3.4 log's BAR3: 'QffcfI' adds up to 29 bytes, the FMT says 33): its
  // messages are skipped by the FMT's length, and the log's description says so.
  DataFlashWriter wild = copter4(2);
  wild.fmt(199, "BAR3", "QffcfI", "TimeUS,Alt,Press,Temp,CRt,SMS", 33)
      .message(199, std::string(30, '\x07'))
      .message(140, imu4(1, 2, 1.0f).bytes());
  wild.save(file);
  const LogContents c = read_dataflash(file);
  EXPECT_EQ(c.sensors.at(1).samples, 3u);
  ASSERT_EQ(c.skipped_types.size(), 1u);
  EXPECT_NE(c.describe().find("skipped (not read): FMT of type 199 'BAR3' (format 'QffcfI'): the format adds up to 29 "
                              "bytes with the header, the FMT says 33"),
            std::string::npos)
      << c.describe();
}

TEST(DataFlash, AnInstanceTheFileDoesNotHold) {
  ScratchDir dir;
  DataFlashWriter none;
  other_messages(none);
  testing::expect_gyro_choice(read_dataflash, dir / "copter4.bin", copter4(), 3, "0 and 1", none, "DataFlash");
}

}  // namespace
}  // namespace gyrotherm::fit
