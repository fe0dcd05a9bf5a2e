// The gyro: a rate in °/h. Its white noise is the angle random walk
// (°/√h = √q_w/60 for q_w in (°/h)²·s), its random walk the rate random
// walk (°/h/√h = 60·√q_r for q_r in (°/h)²/s).
#include "fit/data/sensor_kind.h"

namespace gyrotherm::fit {

const SensorKind& gyro_sensor() {
  static const SensorKind kind{
      .name = "gyro",
      .noun = "gyro",
      .quantity = Quantity::gyro,
      .unit = "°/h",
      .column = "gyro_dph",
      .words = "gyr omega",
      .noise = {{{"arw", "deg/sqrt(h)", 1.0 / 60.0},
                 {"bias_instability", "deg/h", 1.0},
                 {"gauss_markov", "deg/h", 1.0},
                 {"rrw", "deg/h/sqrt(h)", 60.0}}},
      .is_gyro = true};
  return kind;
}

}  // namespace gyrotherm::fit
