// simulate's PX4 ULog (sim/record_format.h), written from PX4's ULog
// specification (PX4-Autopilot docs/en/dev_log/ulog_file_format.md): the
// 16-byte header, the flag bits, a format, two information messages and a
// subscription per topic, then one data message per sensor per sample.
// Fields as msg/SensorGyro.msg, SensorAccel.msg and SensorBaro.msg name them
// (the ones a reader needs: timestamp, device_id, the axes, temperature).
#include <cmath>
#include <vector>

#include "sim/record_format.h"
#include "sim/simulator.h"
#include "sim/util/little_endian.h"

namespace gyrotherm::sim {
namespace {

struct Topic {
  std::uint16_t msg_id;
  const char* name;
  const char* fields;  // after timestamp and device_id
  std::uint32_t device_id;  // made up, one per sensor
  std::vector<const std::vector<double>*> values;
  double scale;  // to the topic's unit
};

void message(Packer& out, char type, const std::string& payload) {
  out.put(static_cast<std::uint16_t>(payload.size())).put(static_cast<std::uint8_t>(type)).raw(payload);
}

std::vector<Topic> topics(const GyroConfig& gyro, const SimulationResult& r) {
  std::vector<Topic> out;
  auto axes = [&](std::string_view kind) {
    return std::vector<const std::vector<double>*>{&channel_values(gyro, r, kind, 'x'), &channel_values(gyro, r, kind, 'y'),
                                                   &channel_values(gyro, r, kind, 'z')};
  };
  out.push_back({0, "sensor_gyro", "float x;float y;float z;", 1310988, axes("gyro"), kRadPerSecondPerDph});
  if (channel_index(gyro, "accel", 'x') >= 0)
    out.push_back({1, "sensor_accel", "float x;float y;float z;", 1310996, axes("accel"), 1.0});
  if (const int b = channel_index(gyro, "baro", 0); b >= 0)
    out.push_back({2, "sensor_baro", "float pressure;", 6620172, {&r.channels[static_cast<std::size_t>(b)].value}, 1.0});
  return out;
}

}  // namespace

void check_ulog_channels(const GyroConfig& gyro, const std::filesystem::path& gyro_file) {
  require_axes(gyro, gyro_file, "gyro", "a ULog's sensor_gyro");
  if (channel_index(gyro, "accel", 'x') >= 0 || channel_index(gyro, "accel", 'y') >= 0 ||
      channel_index(gyro, "accel", 'z') >= 0)
    require_axes(gyro, gyro_file, "accel", "a ULog's sensor_accel");
}

std::string ulog_record(const Simulator& simulator, const SimulationResult& r) {
  const std::vector<Topic> list = topics(simulator.gyro(), r);
  Packer out;
  out.raw("ULog").put<std::uint8_t>(0x01).put<std::uint8_t>(0x12).put<std::uint8_t>(0x35);
  out.put<std::uint8_t>(1).put<std::uint64_t>(0);
  message(out, 'B', std::string(40, '\0'));  // no compat, incompat or appended data
  for (const Topic& t : list)
    message(out, 'F', std::string(t.name) + ":uint64_t timestamp;uint32_t device_id;" + t.fields +
                          "float temperature;");
  auto info = [&](const std::string& key, const std::string& value) {
    message(out, 'I', Packer().put(static_cast<std::uint8_t>(key.size())).raw(key).raw(value).bytes());
  };
  info("char[18] sys_name", "gyrotherm simulate");
  info("uint32_t ver_sw_release", Packer().put<std::uint32_t>(0x010F00FF).bytes());  // v1.15.0: pressure in Pa
  for (const Topic& t : list)
    message(out, 'A', Packer().put<std::uint8_t>(0).put(t.msg_id).raw(t.name).bytes());
  for (std::size_t k = 0; k < r.rows(); ++k) {
    const auto time_us = static_cast<std::uint64_t>(std::llround(r.time_s[k] * 1e6));
    for (const Topic& t : list) {
      Packer p;
      p.put(t.msg_id).put(time_us).put(t.device_id);
      for (const std::vector<double>* v : t.values) p.put(static_cast<float>((*v)[k] * t.scale));
      p.put(static_cast<float>(r.temp_c[k]));
      message(out, 'D', p.bytes());
    }
  }
  return out.take();
}

}  // namespace gyrotherm::sim
