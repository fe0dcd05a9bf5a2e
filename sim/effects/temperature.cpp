// T: the gyro temperature itself, r = T (°C). Its true coefficient is the
// paper's b1, the gyro file's [truth] b1_dph_per_c.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature{
    .name = "T",
    .meaning = "temperature sensitivity",
    .unit = "°C",
    .truth_key = "b1_dph_per_c",
    .family = Family::temperature_power,
    .c_form = {.expression = "T"},
    .temperature_power = 1,
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) {
      return s.temp_c[p];
    })>,
};

}  // namespace gyrotherm::effects
