#pragma once
// The channels a gyro file may simulate beside its gyro: further gyro axes,
// an accelerometer's axes and a barometer. Each is a bias model in its own
// unit on the same thermal network (a sensor kind is a bias model and units,
// not new physics):
//
//   value(t) = b0 + Σ_k c_k·r_k(t; θ_k) + white noise           [the kind's unit]
//
// over the effects of the registry (sim/effects/effect.h) by term name, each
// r_k on the same true state as the gyro's (the sensor's temperature, its
// rate, the far side...), θ_k the gyro file's [hidden] parameters. The white
// noise is a density in unit·√s: a sample at rate f scatters by density·√f.
// The gyro's own [truth] is axis x of its kind.
//
// A gyro file lists them as [[channel]] tables (docs/contracts.md,
// "Simulator input"); the CSV gains a column and its truth per channel, and
// only a gyro file with every axis of a kind can be written as an autopilot
// log (sim/autopilot_log_writer.h).

#include <map>
#include <span>
#include <string>
#include <string_view>

namespace gyrotherm::sim {

// A kind a channel may be: its name as the gyro file writes it, its unit,
// the unit as a column's suffix, and whether it has axes.
struct ChannelKind {
  std::string_view name;  // gyro, accel, baro
  std::string_view unit;  // °/h, m/s², Pa
  std::string_view suffix;  // dph, mps2, pa
  bool has_axes = true;
};
// nullptr when `name` is none of them.
const ChannelKind* find_channel_kind(std::string_view name);
// "gyro, accel or baro".
std::string channel_kind_names();

struct ChannelConfig {
  const ChannelKind* kind = nullptr;
  char axis = 'x';  // 'x', 'y' or 'z'; 0 for a kind without axes
  double b0 = 0.0;  // the constant, in the kind's unit (gravity or the atmosphere included)
  std::map<std::string, double> coefficient;  // by term name, in the kind's unit per the term's
  double white_noise = 0.0;                   // density, unit·√s
  int line = 0;                               // of its [[channel]] in the gyro file

  // Its CSV column and the column of its noise-free value:
  // accel_x_mps2 / accel_x_true_mps2, baro_pa / baro_true_pa.
  std::string column() const;
  std::string truth_column() const;
  std::string stem() const;  // accel_x, baro
  // "accel x", "baro".
  std::string label() const;
  // The true coefficients by term name, b0 under "1", every term that is on.
  std::map<std::string, double> true_coefficients() const;
};

}  // namespace gyrotherm::sim
