#pragma once
// The kinds of sensor whose bias a record's measured channel holds: a gyro
// (a rate, °/h), an accelerometer (a specific force, m/s²), a barometer (a
// pressure, Pa) or a magnetometer (a flux density, gauss). The thermal model, the fit and its intervals are the same
// for each; what differs is the quantity and its units, the default column,
// the names the noise components go by (a gyro's white noise is an angle
// random walk in °/√h, an accelerometer's a velocity random walk in m/s/√h),
// and the checks that only make sense for a gyro (a rate at rest).
//
// Adding a kind: its entry (and its physics in words) in the table in
// fit/data/sensor_kind.cpp, as a unit is a line in units.cpp, and its test
// in tests/sensor_kind_test.cpp.

#include <algorithm>
#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fit/data/units.h"

namespace gyrotherm::fit {

// A noise component's name and unit as a fit reports it (the unit in ASCII
// as the JSON keeps it; the text report writes it with °, √ and ²), and for
// the white noise and the random walk the factor from the square root of the
// model's amplitude (q_w in base²·s, q_r in base²/s) to the reported value.
struct NoiseName {
  std::string_view name;
  std::string_view unit;
  double factor = 1.0;
};

struct SensorKind {
  std::string_view name;     // as --sensor takes it: gyro, accel, baro, mag
  std::string_view noun;     // "gyro", "accelerometer", "barometer"
  Quantity quantity;         // its units in fit/data/units.cpp
  std::string_view unit;     // the base unit as reports write it: "°/h", "m/s²", "Pa"
  std::string_view column;   // the default column of a CSV: gyro_dph, accel_mps2, baro_pa
  // How loggers name its columns: a word of the name starting with one of
  // these ("gyr": GyrX, gyro_z; "acc": imu.acc.x, AccX; "baro press": BARO.Press).
  std::string_view words;
  // White noise, bias instability (flicker), Gauss–Markov, random walk.
  std::array<NoiseName, 4> noise;
  bool is_gyro = false;      // the rate checks (a rate at rest, an implausible angle random walk)
  // How an autopilot log holds it (fit/data/autopilot_log.h): ULog, the topic
  // (its multi_id the instance) and the fields; DataFlash, the messages (the
  // first with the instance in `I`, or one per instance: IMU, IMU2, IMU3) and
  // the labels, none where the format logs no temperature beside it; and the
  // unit the fields are in.
  struct LogNaming {
    std::string_view messages, fields, unit;
  };
  LogNaming ulog, dataflash;
  std::string_view log_columns;  // the columns a log's samples are read as: "gyro_x,gyro_y,gyro_z"
  // How many axes it has: 3, or 1 (a barometer: the pressure).
  std::size_t axes() const { return static_cast<std::size_t>(std::count(log_columns.begin(), log_columns.end(), ',')) + 1; }
  // What the autopilots store of its thermal compensation, in the unit
  // their logs use (ulog.unit): PX4's parameter stem (TC_G, TC_A, TC_B,
  // TC_M) and its polynomial's order (3; the barometer's 5); ArduPilot's
  // INS_TCAL group (GYR, ACC), empty where ArduPilot has none.
  std::string_view px4_stem;
  int px4_order = 3;
  std::string_view ardupilot_group;
  // PX4's calibration parameters' stem: CAL_GYRO (CAL_GYRO0_ID), CAL_ACC, CAL_BARO, CAL_MAG.
  std::string_view px4_calibration;
};

// Every kind, in the registry's order (gyro first).
std::span<const SensorKind> sensor_kinds();
// The kind named `name` (empty: the gyro); throws InputError naming
// --sensor and the known names.
const SensorKind& sensor_kind(std::string_view name);
// "gyro, accel or baro".
std::string sensor_kind_names();
// The words of one of the kinds' space-separated lists ("x y z", "IMU IMU2 IMU3").
std::vector<std::string_view> words_in(std::string_view list);
// A unit as the text reports write it (°/√h, m/s²·√s), from the ASCII form
// the JSON keeps (deg/sqrt(h), m/s^2*sqrt(s)).
std::string shown_unit(std::string_view ascii);
// Whether column `name`'s words (fit/data/column_role.h) name `kind`: one
// starts with one of kind.words, and none with "temp" (a sensor's
// temperature column).
bool names_sensor(std::string_view name, const SensorKind& kind);

}  // namespace gyrotherm::fit
