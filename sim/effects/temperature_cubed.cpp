// T^3: r = T³ (°C³), higher-order curvature of the temperature sensitivity
// (a hidden effect: [hidden] T^3 = COEF).
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_cubed{
    .name = "T^3",
    .meaning = "higher-order curvature",
    .unit = "°C³",
    .family = Family::temperature_power,
    .c_form = {.expression = "T * T * T"},
    .temperature_power = 3,
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) {
      return s.temp_c[p] * s.temp_c[p] * s.temp_c[p];
    })>,
};

}  // namespace gyrotherm::effects
