// The barometer: a static pressure in Pa. In a thermal chamber at constant
// pressure its reading's change with temperature is the sensor's offset;
// outside one, the weather moves it too (a fit cannot tell the two apart).
// Its white noise is given as a pressure density (Pa·√s = √q_w for q_w in
// Pa²·s), its random walk in Pa/√h (60·√q_r for q_r in Pa²/s).
#include "fit/data/sensor_kind.h"

namespace gyrotherm::fit {

const SensorKind& baro_sensor() {
  static const SensorKind kind{
      .name = "baro",
      .noun = "barometer",
      .quantity = Quantity::pressure,
      .unit = "Pa",
      .column = "baro_pa",
      .words = "baro press",
      .noise = {{{"white_noise", "Pa*sqrt(s)", 1.0},
                 {"bias_instability", "Pa", 1.0},
                 {"gauss_markov", "Pa", 1.0},
                 {"pressure_random_walk", "Pa/sqrt(h)", 60.0}}},
      .is_gyro = false};
  return kind;
}

}  // namespace gyrotherm::fit
