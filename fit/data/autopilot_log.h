#pragma once
// Reading the gyros of an autopilot's binary flight log (docs/contracts.md,
// "Autopilot logs (ULog, DataFlash)"): for each gyro (IMU instance) the log
// holds, its samples — time, temperature and the three rates — read in one
// pass over the file in blocks (memory: the format table and one message).
//
// PX4 ULog (fit/data/ulog.cpp). Reference: PX4-Autopilot,
// docs/en/dev_log/ulog_file_format.md ("ULog File Format").
//
//   file    = header { message }
//   header  = "ULog" 01 12 35, version (uint8), start time (uint64 µs)  16 bytes
//   message = size (uint16, the payload's), type (char), payload
//
// 'F' defines a format "name:type field;type field;..." (types: the C
// integer types, float, double, bool, char, arrays "float[3]", other formats
// nested; fields named _padding* are skipped and a trailing one may be left
// out of a data message); 'A' subscribes a format as msg_id with a multi_id
// (the instance); 'D' is msg_id and the packed fields. The gyros are the
// subscriptions of `sensor_gyro`: fields read by name at the offsets the
// file's own format gives (`timestamp` µs, `x` `y` `z` rad/s, `temperature`
// °C when present, `device_id` when present), since PX4 versions differ in
// the set, order and padding of the fields. 'B' flag bits: data appended after
// a cut message (incompat bit 0) is read as the spec says; any other
// incompatible bit is refused. Other message types are skipped, as the spec
// asks of a parser.
//
// ArduPilot DataFlash (.bin, fit/data/dataflash.cpp). Reference: ArduPilot,
// libraries/AP_Logger/LogStructure.h (the FMT message and the format
// characters) and libraries/AP_InertialSensor/LogStructure.h (IMU).
//
//   message = A3 95, type (uint8), payload (length from the type's FMT)
//   FMT (type 128) = type B, length B (whole message), name n, format N, labels Z
//   format characters: b B h H i I f d n N Z c C e E L M q Q a g (sizes 1 1 2 2
//   4 4 4 8 4 16 64 2 2 4 4 4 1 8 8 64 2; c C ×0.01, e E ×0.01, L ×1e-7)
//
// The gyros are the IMU messages, fields read by label from the file's FMT:
// Copter 4.x `IMU` with the instance in `I`; Copter 3.6 `IMU`, `IMU2`, `IMU3`
// (instances 0, 1, 2); time `TimeUS` (µs; `TimeMS` in ms in logs before 3.3),
// `GyrX` `GyrY` `GyrZ` rad/s, temperature `T` (`Temp` before 3.6) °C.
//
// Bad input — a file that is not the format, a corrupt message, a format
// that cannot be read, an instance the file does not hold — throws
// gyrotherm::InputError naming the file, the byte offset, what was expected
// and what is there. A file ending inside a message (power cut) is not an
// error: it is read up to there and LogContents::truncated says so.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace gyrotherm::fit {

// One gyro (IMU instance) the log holds.
struct LogGyro {
  int instance = 0;             // ULog multi_id of sensor_gyro; DataFlash the I field, or IMU/IMU2/IMU3 -> 0/1/2
  std::string message;          // "sensor_gyro", "IMU", "IMU2", "IMU3"
  std::uint32_t device_id = 0;  // ULog sensor_gyro.device_id (first sample) when present, else 0
  std::size_t samples = 0;
  std::size_t samples_with_temperature = 0;  // a finite temperature
  double first_time_s = NAN, last_time_s = NAN, temp_min_c = NAN, temp_max_c = NAN;
};

// The accelerometer of an IMU instance (DataFlash IMU AccX, AccY, AccZ; ULog
// sensor_accel x, y, z of that multi_id), m/s²: what tells a vehicle that
// moves from a gyro at rest. A sample shows motion when its magnitude is more
// than kAccelMagnitudeLimit from 1 g, or its direction more than
// kAccelTiltLimitDeg from the instance's first sample's (a thermal test keeps
// the gyro still; vibration and turns move both).
inline constexpr double kStandardGravity = 9.80665;
inline constexpr double kAccelMagnitudeLimit = 1.5;  // m/s²
inline constexpr double kAccelTiltLimitDeg = 5.0;
struct LogAccel {
  int instance = 0;
  std::size_t samples = 0, moving = 0;
  double largest_tilt_deg = 0.0, largest_magnitude_error = 0.0;  // from the first sample's direction; from 1 g
  double first[3] = {NAN, NAN, NAN};
  double moving_share() const { return samples == 0 ? 0.0 : static_cast<double>(moving) / static_cast<double>(samples); }
};

struct LogContents {
  std::string format;                   // "ULog v1" / "DataFlash"
  std::vector<LogGyro> gyros;           // by instance, lowest first
  std::vector<LogAccel> accels;         // by instance, lowest first (none when the log has no accelerometer)
  // The autopilot's parameters as the log records them (ULog 'P' messages,
  // DataFlash PARM), each name's first value: what was active when it was
  // written (e.g. TC_G_ENABLE, INS_TCAL1_ENABLE).
  std::map<std::string, double, std::less<>> parameters;
  const LogAccel* accel(int instance) const;
  bool truncated = false;               // the file ends inside a message (power cut): read up to there
  std::uint64_t truncated_at_byte = 0;  // where that message starts, when truncated
  // Message types the reader does not need whose FMT contradicts itself (its
  // format adds up to another length than it gives): skipped by the length
  // the FMT gives, as pymavlink's DFReader does.
  struct SkippedType {
    int type = 0;
    std::string name, format;
    std::size_t format_bytes = 0, fmt_length = 0;  // with the 3-byte header
  };
  std::vector<SkippedType> skipped_types;

  // "ULog v1: sensor_gyro instance 0 (device 2621450): 6 samples, 12.5..17.5 s,
  // 40.03..40.36 °C; sensor_gyro instance 2 (...): ..., temperature NaN throughout"
  std::string describe() const;
  // The default choice: the first gyro (lowest instance) with at least 2
  // samples with a finite temperature; -1 if none.
  int default_instance() const;
  // "0, 1 and 2" (the instances held), or "none".
  std::string instances() const;
};

// One sample of the chosen gyro: time in s (the log's µs timestamp / 1e6),
// temperature °C (NaN if the sample has none), x y z rad/s.
using GyroSampleSink = std::function<void(double time_s, double temp_c, double x, double y, double z)>;

// Reads the whole file once and returns what it holds. With a sink, every
// sample of gyro `instance` goes to it in file order; with an empty sink only
// the contents are gathered. A sink with instance -1 takes the default
// instance (the file is then read twice: contents, then samples). Throws
// InputError (file, byte offset, what was expected) on a file that is not that
// format, a corrupt message, or an `instance` not held (listing those held).
LogContents read_ulog(const std::filesystem::path& file, int instance = -1, const GyroSampleSink& sink = {});
LogContents read_dataflash(const std::filesystem::path& file, int instance = -1, const GyroSampleSink& sink = {});

// The binary log formats, a registry as the effects and the exporters are:
// a format is one file (its reader, defining `LogFormat NAME_log_format()`),
// one line LOG_FORMAT(NAME) in fit/data/log_formats.def and one test. A file
// is a format's when it starts with that format's magic bytes; a file that
// starts with none of them is read as a text table (CSV).
using AutopilotReader = LogContents (*)(const std::filesystem::path& file, int instance, const GyroSampleSink& sink);
struct LogFormat {
  std::string_view name;   // "ulog": what autopilot_log_format gives
  std::string_view title;  // "ULog": how LogContents::format begins ("ULog v1")
  std::string_view magic;  // the bytes every file of the format starts with
  AutopilotReader read;
};
const std::vector<LogFormat>& log_format_registry();
// The format whose magic the file starts with; nullptr for any other file (a
// CSV) and for a file that cannot be opened (its reader reports that).
const LogFormat* log_format_of(const std::filesystem::path& file);
// log_format_of's name, or "" for a text table.
std::string autopilot_log_format(const std::filesystem::path& file);
// Whether a unit's source text ("ULog v1 sensor_gyro 0") names a binary
// format, whose files state their units.
bool stated_by_log_format(std::string_view source);

#define LOG_FORMAT(name) LogFormat name##_log_format();
#include "fit/data/log_formats.def"
#undef LOG_FORMAT

}  // namespace gyrotherm::fit
