// d2T: r = d²T/dt² (°C/s²), the second-order part of a thermal lag between
// the sensor and the cavity (see also lag, its first-order filter form).
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_acceleration{
    .name = "d2T", .meaning = "sensor-to-cavity thermal lag", .unit = "°C/s²", .family = Family::rate, .c_form = {"accel"},
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) { return s.accel_c_per_s2[p]; })>};

}  // namespace gyrotherm::effects
