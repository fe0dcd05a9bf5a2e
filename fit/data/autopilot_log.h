#pragma once
// Reading the sensors of one kind (fit/data/sensor_kind.h: gyro,
// accelerometer, barometer, magnetometer) from an autopilot's binary flight
// log (docs/contracts.md, "Autopilot logs (ULog, DataFlash)"): for each
// instance of that kind the log holds, its samples — time, temperature and
// the three axes (the barometer: one, the pressure) — read in one pass over
// the file in blocks (memory: the format table and one message).
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
// (the instance); 'D' is msg_id and the packed fields. A kind's instances are
// the subscriptions of its topic (`sensor_gyro`, `sensor_accel`,
// `sensor_baro`, `sensor_mag`): fields read by name at the offsets the file's
// own format gives (`timestamp` µs, `x` `y` `z` in rad/s, m/s² or gauss, or
// `pressure`, `temperature` °C when present, `device_id` when present), since
// PX4 versions differ in the set, order and padding of the fields. PX4 logs
// `pressure` in Pa from v1.13 on and in mbar before (PX4 pull request 19284,
// 2022): the information message `ver_sw_release` (0xAABBCCTT: major AA,
// minor BB) tells which; a log without it is read by its values (an
// atmosphere is about 1e5 Pa or 1e3 mbar) and LogContents::unit_from says so. 'B' flag bits: data appended after
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
// The gyros and accelerometers are the IMU messages, the barometers the
// BARO messages, fields read by label from the file's FMT: Copter 4.x `IMU`
// and `BARO` with the instance in `I`; Copter 3.6 `IMU`, `IMU2`, `IMU3` and
// `BARO`, `BAR2`, `BAR3` (instances 0, 1, 2); time `TimeUS` (µs; `TimeMS` in
// ms in logs before 3.3), `GyrX` `GyrY` `GyrZ` rad/s, `AccX` `AccY` `AccZ`
// m/s², `Press` Pa, temperature `T` (`Temp` before 3.6, and in BARO) °C. The
// MAG message has no temperature: a DataFlash magnetometer is refused.
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

#include "fit/data/sensor_kind.h"

namespace gyrotherm::fit {

// One sensor instance of the kind read that the log holds.
struct LogSensor {
  int instance = 0;             // ULog multi_id of the topic; DataFlash the I field, or IMU/IMU2/IMU3 -> 0/1/2
  std::string message;          // "sensor_gyro", "sensor_baro", "IMU", "IMU2", "BARO"
  std::uint32_t device_id = 0;  // ULog device_id (first sample) when present, else 0
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
  const SensorKind* kind = nullptr;     // the kind read (never null in a reader's result)
  std::vector<LogSensor> sensors;       // of that kind, by instance, lowest first
  // The unit the samples are in (a name in fit/data/units.cpp: "rad/s",
  // "mps2", "Pa", "mbar", "gauss"), and, when the format does not fix it,
  // how it was told ("ver_sw_release v1.11", "pressure 1003: an atmosphere
  // in mbar").
  std::string unit, unit_from;
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
  // The default choice: the first instance (lowest) with at least 2
  // samples with a finite temperature; -1 if none.
  int default_instance() const;
  // "0, 1 and 2" (the instances held), or "none".
  std::string instances() const;
};

// One sample of the chosen instance: time in s (the log's µs timestamp /
// 1e6), temperature °C (NaN if the sample has none), x y z in
// LogContents::unit (a barometer: x the pressure, y and z NaN).
using SampleSink = std::function<void(double time_s, double temp_c, double x, double y, double z)>;

// Reads the whole file once and returns what it holds of `kind`. With a
// sink, every sample of `instance` goes to it in file order; with an empty
// sink only the contents are gathered. A sink with instance -1 takes the
// default instance (the file is then read twice: contents, then samples).
// Throws InputError (file, byte offset, what was expected) on a file that is
// not that format, a corrupt message, an `instance` not held (listing those
// held), or a kind the format cannot give with a temperature.
LogContents read_ulog(const std::filesystem::path& file, int instance = -1, const SampleSink& sink = {},
                      const SensorKind& kind = sensor_kinds().front());
LogContents read_dataflash(const std::filesystem::path& file, int instance = -1, const SampleSink& sink = {},
                           const SensorKind& kind = sensor_kinds().front());

// The binary log formats, a registry as the effects and the exporters are:
// a format is one file (its reader, defining `LogFormat NAME_log_format()`),
// one line LOG_FORMAT(NAME) in fit/data/log_formats.def and one test. A file
// is a format's when it starts with that format's magic bytes; a file that
// starts with none of them is read as a text table (CSV).
using AutopilotReader = LogContents (*)(const std::filesystem::path& file, int instance, const SampleSink& sink,
                                        const SensorKind& kind);
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
