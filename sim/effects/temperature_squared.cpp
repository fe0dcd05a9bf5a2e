// T^2: r = T² (°C²), the curvature of the temperature sensitivity; the
// paper's b2, [truth] b2_dph_per_c2.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_squared{
    .name = "T^2",
    .meaning = "curvature of the sensitivity",
    .unit = "°C²",
    .truth_key = "b2_dph_per_c2",
    .family = Family::temperature_power,
    .c_form = {.expression = "T * T"},
    .temperature_power = 2,
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) {
      return s.temp_c[p] * s.temp_c[p];
    })>,
};

}  // namespace gyrotherm::effects
