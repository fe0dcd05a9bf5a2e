#pragma once
// Three-axis IMU samples written as the autopilots log them, for the tests
// of reading (log_reading_test) and of `check` (cli_check_test): PX4's
// sensor_gyro (v1.14 layout; instance 0 without a temperature, instance 1
// with the samples) and sensor_accel, ArduPilot Copter 4.x IMU messages of
// instance 0; and the parameters each logs (ULog 'P', DataFlash PARM).

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "autopilot_log_writer.h"

namespace gyrotherm::testing {

// One sample of a three-axis gyro as a log holds it (32-bit floats, µs).
struct ImuSample {
  std::uint64_t time_us;
  float temp_c, x, y, z;                   // °C, rad/s
  float ax = 0.0f, ay = 0.0f, az = -9.80665f;  // m/s², at rest level
};

using LoggedParameters = std::vector<std::pair<std::string, float>>;

// The gyro of instance 1 has device id kUlogDeviceId (instance 0: 2621450).
inline constexpr std::uint32_t kUlogDeviceId = 2490378;

inline void write_ulog(const std::filesystem::path& file, const std::vector<ImuSample>& samples,
                       const LoggedParameters& parameters = {}) {
  ULogWriter w;
  w.flag_bits().format(
      "sensor_gyro:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
      "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;uint8_t[4] _padding0;");
  w.format("sensor_accel:uint64_t timestamp;uint64_t timestamp_sample;uint32_t device_id;float x;float y;float z;"
           "float temperature;uint32_t error_count;uint8_t[3] clip_counter;uint8_t samples;uint8_t[4] _padding0;");
  for (const auto& [name, value] : parameters) w.parameter(name, value);
  w.subscribe(0, 0, "sensor_gyro").subscribe(1, 1, "sensor_gyro").subscribe(1, 2, "sensor_accel");
  for (const ImuSample& s : samples) {
    for (const std::uint16_t id : {std::uint16_t{0}, std::uint16_t{1}}) {
      Packer p;
      p.put(s.time_us).put(s.time_us).put<std::uint32_t>(id == 0 ? 2621450 : kUlogDeviceId);
      p.put(s.x).put(s.y).put(s.z).put(id == 0 ? std::nanf("") : s.temp_c).put<std::uint32_t>(0).zeros(3);
      p.put<std::uint8_t>(1);
      w.data(id, p);
    }
    Packer a;
    a.put(s.time_us).put(s.time_us).put<std::uint32_t>(kUlogDeviceId).put(s.ax).put(s.ay).put(s.az).put(s.temp_c);
    a.put<std::uint32_t>(0).zeros(3).put<std::uint8_t>(1);
    w.data(2, a);
  }
  w.save(file);
}

inline void write_dataflash(const std::filesystem::path& file, const std::vector<ImuSample>& samples,
                            const LoggedParameters& parameters = {}) {
  DataFlashWriter w;
  w.fmt(64, "PARM", "QNff", "TimeUS,Name,Value,Default");
  for (const auto& [name, value] : parameters) {
    Packer p;
    p.put<std::uint64_t>(1000).text(name, 16).put(value).put(0.0f);
    w.message(64, p.bytes());
  }
  w.fmt(99, "IMU", "QBffffffIIfBBHH", "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz");
  for (const ImuSample& s : samples) {
    Packer p;
    p.put(s.time_us).put<std::uint8_t>(0).put(s.x).put(s.y).put(s.z).put(s.ax).put(s.ay).put(s.az);
    p.put<std::uint32_t>(0).put<std::uint32_t>(0).put(s.temp_c).put<std::uint8_t>(1).put<std::uint8_t>(1);
    p.put<std::uint16_t>(400).put<std::uint16_t>(400);
    w.message(99, p.bytes());
  }
  w.save(file);
}

}  // namespace gyrotherm::testing
