// The accelerometer: a specific force in m/s² (gravity included: the bias
// is what the thermal model fits, on top of the constant the attitude gives).
// Its white noise is the velocity random walk (m/s/√h = 60·√q_w for q_w in
// (m/s²)²·s), its random walk the acceleration random walk (m/s²/√h =
// 60·√q_r for q_r in (m/s²)²/s). IEEE Std 1293-2018 names them so.
#include "fit/data/sensor_kind.h"

namespace gyrotherm::fit {

const SensorKind& accel_sensor() {
  static const SensorKind kind{
      .name = "accel",
      .noun = "accelerometer",
      .quantity = Quantity::accel,
      .unit = "m/s²",
      .column = "accel_mps2",
      .words = "acc",
      .noise = {{{"vrw", "m/s/sqrt(h)", 60.0},
                 {"bias_instability", "m/s^2", 1.0},
                 {"gauss_markov", "m/s^2", 1.0},
                 {"accel_random_walk", "m/s^2/sqrt(h)", 60.0}}},
      .is_gyro = false};
  return kind;
}

}  // namespace gyrotherm::fit
