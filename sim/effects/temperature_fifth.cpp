// T^5: r = T⁵ (°C⁵), a fifth-order term of the temperature sensitivity: the
// fifth-order fits one MEMS gyro family needs over a wide range (a hidden
// effect: [hidden] T^5 = COEF). PX4 and ArduPilot store cubics: their exports
// refuse it.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_fifth{
    .name = "T^5",
    .meaning = "fifth-order curvature",
    .unit = "°C⁵",
    .family = Family::temperature_power,
    .c_form = {.expression = "T * T * T * T * T"},
    .temperature_power = 5,
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) {
      return s.temp_c[p] * s.temp_c[p] * s.temp_c[p] * s.temp_c[p] * s.temp_c[p];
    })>,
};

}  // namespace gyrotherm::effects
