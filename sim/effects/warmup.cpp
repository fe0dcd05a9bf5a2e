// warmup: r = exp(−(t − t_on)/τ), the turn-on transient of a gyro switched
// on at t_on (the start of a measured record; −∞ for a simulated gyro that
// was running before the record, whose transient has died out). τ (s) is the
// parameter.
#include <cmath>

#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect warmup{
    .name = "warmup",
    .meaning = "turn-on transient",
    .unit = "1",
    .columns = kTime,
    .parameter = EffectParameter{.name = "time_constant_s",
                                 .gyro_key = "warmup_time_constant_s",
                                 .lower = 60.0,
                                 .upper = 7200.0,
                                 .simulator_default = 1800.0},
    .family = Family::transient,
    .c_form = {.expression = "exp(-rel / {theta})"},
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double tau_s) {
      return std::exp(-(s.time_s[p] - s.switch_on_s) / tau_s);
    })>,
};

}  // namespace gyrotherm::effects
