// Writes the seed files of fuzz_ulog and fuzz_dataflash (tests/fuzz/corpus/ulog,
// tests/fuzz/corpus/dataflash) with the tests' writers (tests/autopilot_log_writer.h):
// small logs in each firmware's current and older layouts, one cut short.
// Run once from the repository's root after changing them:
//   g++ -std=c++20 -Itests tests/fuzz/make_log_seeds.cpp -o /tmp/seeds && /tmp/seeds

#include <cmath>
#include <cstdint>
#include <filesystem>

#include "autopilot_log_writer.h"

using gyrotherm::testing::DataFlashWriter;
using gyrotherm::testing::Packer;
using gyrotherm::testing::ULogWriter;

namespace {

Packer gyro_current(int i, int k) {
  Packer p;
  const std::uint64_t t = 1'000'000 + 4000 * static_cast<std::uint64_t>(k) + static_cast<std::uint64_t>(i);
  p.put(t).put(t - 50).put(static_cast<std::uint32_t>(2621450 + i));
  p.put(0.01f * static_cast<float>(k)).put(-0.02f).put(0.03f * static_cast<float>(i));
  p.put(i == 1 ? NAN : 35.5f + 0.25f * static_cast<float>(k)).put<std::uint32_t>(0).zeros(3).put<std::uint8_t>(1);
  return p;
}

Packer imu(int i, int k, bool with_instance, bool with_rates_hz) {
  Packer p;
  p.put(60'000'000 + 2500 * static_cast<std::uint64_t>(k));
  if (with_instance) p.put(static_cast<std::uint8_t>(i));
  p.put(0.001f * static_cast<float>(k)).put(0.002f).put(-0.003f).put(0.1f).put(0.2f).put(-9.8f);
  p.put<std::uint32_t>(0).put<std::uint32_t>(0).put(44.0f + 0.5f * static_cast<float>(k + i));
  p.put<std::uint8_t>(1).put<std::uint8_t>(1);
  if (with_rates_hz) p.put<std::uint16_t>(1000).put<std::uint16_t>(1000);
  return p;
}

}  // namespace

int main() {
  namespace fs = std::filesystem;
  const fs::path ulog = "tests/fuzz/corpus/ulog", dataflash = "tests/fuzz/corpus/dataflash";
  fs::create_directories(ulog);
  fs::create_directories(dataflash);

  ULogWriter current;
  current.flag_bits().info("char[3] sys_name", "PX4").parameter("IMU_GYRO_RATEMAX", 400.0f);
  current.format(
      "sensor_gyro:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
      "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;uint8_t[4] _padding0;");
  current.format("vehicle_status:uint64_t timestamp;uint8_t arming_state;uint8_t[7] _padding0;");
  current.format("sensor_accel:uint64_t timestamp;uint32_t device_id;float x;float y;float z;float temperature;");
  current.parameter("TC_G_ENABLE", 0.0f);
  current.subscribe(1, 0, "sensor_gyro").subscribe(0, 1, "sensor_gyro").subscribe(0, 2, "vehicle_status");
  current.subscribe(0, 4, "sensor_accel");
  for (int k = 0; k < 4; ++k) {
    current.data(1, gyro_current(0, k)).data(0, gyro_current(1, k));
    current.data(2, Packer().put<std::uint64_t>(1'000'000 + 4000 * static_cast<std::uint64_t>(k)).put<std::uint8_t>(2));
    current.data(4, Packer().put<std::uint64_t>(1'000'000 + 4000 * static_cast<std::uint64_t>(k)).put<std::uint32_t>(1).put(0.1f).put(
                        0.2f * static_cast<float>(k)).put(-9.8f).put(35.0f));
    if (k == 1) current.logging("armed", 1'004'000).sync().dropout(5);
  }
  current.save(ulog / "current.ulg");
  gyrotherm::testing::write_bytes(ulog / "truncated.ulg", current.bytes().substr(0, current.size() - 9));

  ULogWriter nested(1);
  nested.format(
      "sensor_gyro:uint64_t timestamp;gyro_raw raw;uint8_t[3] _padding0;float x;float y;float z;"
      "float temperature;uint32_t device_id;");
  nested.format("gyro_raw:int16_t[3] v;uint8_t flags;");
  nested.subscribe(2, 3, "sensor_gyro");
  for (int k = 0; k < 3; ++k) {
    Packer p;
    p.put(1'000'000 + 4000 * static_cast<std::uint64_t>(k)).put<std::int16_t>(1).put<std::int16_t>(2);
    p.put<std::int16_t>(3).put<std::uint8_t>(0).zeros(3).put(0.5f).put(-0.5f).put(0.25f).put(29.0f +
                                                                                             static_cast<float>(k));
    p.put<std::uint32_t>(1311244);
    nested.data(3, p);
  }
  nested.save(ulog / "nested.ulg");

  const char* labels36 = "TimeUS,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz";
  DataFlashWriter copter4;
  copter4.fmt(160, "PARM", "QNf", "TimeUS,Name,Value");
  copter4.fmt(140, "IMU", "QBffffffIIfBBHH", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz");
  copter4.message(160, Packer().put<std::uint64_t>(1).text("INS_GYRO_FILTER", 16).put(20.0f).bytes());
  for (int k = 0; k < 4; ++k)
    for (const int i : {0, 1}) copter4.message(140, imu(i, k, true, true).bytes());
  copter4.save(dataflash / "copter4.bin");
  gyrotherm::testing::write_bytes(dataflash / "truncated.bin", copter4.bytes().substr(0, copter4.size() - 11));

  DataFlashWriter copter36;
  copter36.fmt(131, "IMU", "QffffffIIfBBHH", labels36).fmt(146, "IMU2", "QffffffIIfBBHH", labels36);
  copter36.fmt(147, "IMU3", "QffffffIIfBBHH", labels36);
  for (int k = 0; k < 3; ++k)
    for (const int i : {0, 1, 2})
      copter36.message(static_cast<std::uint8_t>(i == 0 ? 131 : 145 + i), imu(i, k, false, true).bytes());
  copter36.save(dataflash / "copter36.bin");

  DataFlashWriter copter34;
  copter34.fmt(132, "IMU", "QffffffIIfBB", "TimeUS,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,ErrG,ErrA,Temp,GyHlt,AcHlt");
  for (int k = 0; k < 3; ++k) copter34.message(132, imu(0, k, false, false).bytes());
  copter34.save(dataflash / "copter34.bin");
  return 0;
}
