#pragma once
// The formats `simulate` writes its record in, chosen by the output's
// extension (docs/contracts.md, "Simulator output"):
//
//   .ulg   a PX4 ULog: sensor_gyro (rad/s), sensor_accel (m/s²) and
//          sensor_baro (Pa), each sample with the simulated temperature
//          reading (temp_c), one message per sensor per sample;
//   .bin   an ArduPilot DataFlash log: IMU (GyrX.. rad/s, AccX.. m/s², T °C)
//          and BARO (Press Pa, Temp in centidegrees);
//   else   the CSV (sim/output.h).
//
// A log holds a sensor's every axis: the gyro's axis x is the gyro file's
// [truth], y and z and the accelerometer's axes are [[channel]]s
// (sim/channel.h); a kind with no channel is left out (a DataFlash IMU
// message holds the gyro and the accelerometer together, so it needs both).
// The truth JSON goes beside the log as beside a CSV.
//
// Adding a format: its writer in its own file and one line in the table in
// sim/record_format.cpp.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "sim/gyro_config.h"

namespace gyrotherm::sim {

class Simulator;
struct SimulationResult;

struct RecordFormat {
  std::string_view extension;  // ".ulg"; "" for the CSV (every other extension)
  std::string_view name;       // "PX4 ULog"
  // Throws InputError when `gyro` lacks a channel the format needs, naming
  // `gyro_file` and the channels to add.
  void (*check)(const GyroConfig& gyro, const std::filesystem::path& gyro_file);
  std::string (*render)(const Simulator& simulator, const SimulationResult& result);
};

// The format of an output file, by its extension.
const RecordFormat& record_format_for(const std::filesystem::path& output);

// The writers (sim/ulog_record.cpp, sim/dataflash_record.cpp).
std::string ulog_record(const Simulator& simulator, const SimulationResult& result);
std::string dataflash_record(const Simulator& simulator, const SimulationResult& result);
void check_ulog_channels(const GyroConfig& gyro, const std::filesystem::path& gyro_file);
void check_dataflash_channels(const GyroConfig& gyro, const std::filesystem::path& gyro_file);

// The index in gyro.channels of `kind`'s `axis` (0 for a kind without axes),
// or -1; the gyro's axis x is the [truth], -2.
int channel_index(const GyroConfig& gyro, std::string_view kind, char axis);
// The readings of `kind`'s `axis` in `result` (the gyro's axis x: gyro_dph).
const std::vector<double>& channel_values(const GyroConfig& gyro, const SimulationResult& result,
                                          std::string_view kind, char axis);
// The logs' gyro unit, rad/s, per the simulator's °/h.
inline constexpr double kRadPerSecondPerDph = 3.14159265358979323846 / 180.0 / 3600.0;
// Throws InputError unless every axis of `kind` is simulated ("a ULog's
// sensor_gyro holds x, y and z: ...").
void require_axes(const GyroConfig& gyro, const std::filesystem::path& gyro_file, std::string_view kind,
                  std::string_view what);

}  // namespace gyrotherm::sim
