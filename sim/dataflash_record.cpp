// simulate's ArduPilot DataFlash log (sim/record_format.h), written from
// ArduPilot's libraries/AP_Logger/LogStructure.h: every message A3 95 TYPE
// PAYLOAD, the FMT messages first. IMU as ArduPilot 4.x logs it
// (TimeUS,I,GyrX..,AccX..,EG,EA,T,GH,AH,GHz,AHz; rad/s, m/s², °C) and BARO as
// 4.0–4.3 do (TimeUS,I,Alt,Press,Temp,...; Pa, centidegrees).
#include <cmath>
#include <vector>

#include "sim/record_format.h"
#include "sim/simulator.h"
#include "sim/util/little_endian.h"

namespace gyrotherm::sim {
namespace {

constexpr std::uint8_t kFmt = 128, kImu = 131, kBaro = 132;

void message(Packer& out, std::uint8_t type, const std::string& payload) {
  out.put<std::uint8_t>(0xA3).put<std::uint8_t>(0x95).put(type).raw(payload);
}

void format(Packer& out, std::uint8_t type, std::uint8_t length, std::string_view name, std::string_view format,
            std::string_view labels) {
  message(out, kFmt, Packer().put(type).put(length).text(name, 4).text(format, 16).text(labels, 64).bytes());
}

}  // namespace

void check_dataflash_channels(const GyroConfig& gyro, const std::filesystem::path& gyro_file) {
  require_axes(gyro, gyro_file, "gyro", "a DataFlash IMU message");
  require_axes(gyro, gyro_file, "accel", "a DataFlash IMU message");
}

std::string dataflash_record(const Simulator& simulator, const SimulationResult& r) {
  const GyroConfig& gyro = simulator.gyro();
  Packer out;
  format(out, kFmt, 89, "FMT", "BBnNZ", "Type,Length,Name,Format,Columns");
  format(out, kImu, 3 + 8 + 1 + 6 * 4 + 4 + 4 + 4 + 1 + 1 + 2 + 2, "IMU", "QBffffffIIfBBHH",
         "TimeUS,I,GyrX,GyrY,GyrZ,AccX,AccY,AccZ,EG,EA,T,GH,AH,GHz,AHz");
  const int baro = channel_index(gyro, "baro", 0);
  if (baro >= 0)
    format(out, kBaro, 3 + 8 + 1 + 4 + 4 + 2 + 4 + 4 + 4 + 4 + 1, "BARO", "QBffcfIffB",
           "TimeUS,I,Alt,Press,Temp,CRt,SMS,Offset,GndTemp,Health");
  const std::vector<const std::vector<double>*> imu = {
      &channel_values(gyro, r, "gyro", 'x'),  &channel_values(gyro, r, "gyro", 'y'),  &channel_values(gyro, r, "gyro", 'z'),
      &channel_values(gyro, r, "accel", 'x'), &channel_values(gyro, r, "accel", 'y'), &channel_values(gyro, r, "accel", 'z')};
  for (std::size_t k = 0; k < r.rows(); ++k) {
    const auto time_us = static_cast<std::uint64_t>(std::llround(r.time_s[k] * 1e6));
    Packer p;
    p.put(time_us).put<std::uint8_t>(0);
    for (std::size_t a = 0; a < imu.size(); ++a)
      p.put(static_cast<float>((*imu[a])[k] * (a < 3 ? kRadPerSecondPerDph : 1.0)));
    p.put<std::uint32_t>(0).put<std::uint32_t>(0).put(static_cast<float>(r.temp_c[k]));
    p.put<std::uint8_t>(1).put<std::uint8_t>(1).put<std::uint16_t>(0).put<std::uint16_t>(0);
    message(out, kImu, p.bytes());
    if (baro < 0) continue;
    const double pressure = r.channels[static_cast<std::size_t>(baro)].value[k];
    Packer b;
    b.put(time_us).put<std::uint8_t>(0).put(0.0f).put(static_cast<float>(pressure));
    b.put(static_cast<std::int16_t>(std::lround(r.temp_c[k] * 100.0))).put(0.0f).put(static_cast<std::uint32_t>(time_us / 1000));
    b.put(0.0f).put(static_cast<float>(r.temp_c[k])).put<std::uint8_t>(1);
    message(out, kBaro, b.bytes());
  }
  return out.take();
}

}  // namespace gyrotherm::sim
