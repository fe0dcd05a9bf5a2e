#pragma once
// What a log's other column is, by its name and its values, whatever the
// logger's spelling: another motion sensor's channel (a gyro, accelerometer
// or magnetometer axis), a status word or a counter, or a quantity that may
// cause a bias (a case temperature, a supply voltage). Only the last are
// diagnose's candidates by default (studies/diagnose/candidates.h): the
// others move with the platform or the logger, not with the bias's physics.
//
// The name is cut into words at every separator ('.', '_', '[', ' ', …), at
// a lower-to-upper case change and between letters and digits:
// "imu.acc.x" → imu acc x, "IMU.AccX" → imu acc x, "accel_x_mps2" → accel x
// mps 2, "gyro[1]" → gyro 1, "GyrX" → gyr x. A motion sensor is a word
// starting with gyr, acc, mag or omega, MAVLink's xgyro/yacc/zmag, an axis
// word g, a, m or w with x, y or z ("gx", "ay", "m1z", "wz"), or a rate or
// acceleration or field unit in the name ("gy_dph", "ax [m/s^2]",
// "field_uT"). A status is a word such as status, flags, state, mode, valid,
// error, health, crc; a counter a word such as count, counter, seq, index, id,
// or a column whose values step up by the same amount every sample.
// By values: a column that never varies, or takes at most three distinct
// integer values (a flag), is a status.

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gyrotherm::fit {

// derived: a model's, a truth's or a compensation's column (a word true,
// truth, model, compensated or residual: bias_true_dph, accel_x_true_mps2,
// model_dph), never a reading nor a cause.
enum class ColumnRole { cause, motion_sensor, status, counter, constant, derived };
// "a possible cause", "another motion sensor's channel", "a status word", "a counter", "constant",
// "a model's, truth's or compensation's column"
const char* to_string(ColumnRole role);

// The name's words, lower case (as above).
std::vector<std::string> column_words(std::string_view name);
// The name's letters and digits, lower case: names alike but for case and
// separators ("Temp-C", "temp_c") fold alike.
std::string folded_name(std::string_view name);

// By the name alone.
ColumnRole role_by_name(std::string_view name);
// By the name, then by the samples' values (an empty span: the name alone).
ColumnRole column_role(std::string_view name, std::span<const double> values);

}  // namespace gyrotherm::fit
