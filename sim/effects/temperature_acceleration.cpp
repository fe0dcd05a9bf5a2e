// d2T: r = d²T/dt² (°C/s²), the second-order part of a thermal lag between
// the sensor and the cavity (see also lag, its first-order filter form).
#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

void regressor(const EffectSeries& s, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.accel_c_per_s2[p];
}

}  // namespace

extern constinit const Effect temperature_acceleration{
    .name = "d2T",
    .meaning = "sensor-to-cavity thermal lag",
    .unit = "°C/s²",
    .regressor = &regressor,
};

}  // namespace gyrotherm::effects
