// hyst: r = +1 while heating (dT/dt > d), −1 while cooling (dT/dt < −d), 0
// within the dead band |dT/dt| ≤ d: a bias that depends on the direction of
// the temperature change. d (°C/s) is the parameter.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect hysteresis{
    .name = "hyst",
    .meaning = "heating/cooling hysteresis",
    .unit = "1",
    .parameter = EffectParameter{.name = "dead_band_c_per_s",
                                 .gyro_key = "hyst_dead_band_c_per_s",
                                 .lower = 1e-6,
                                 .upper = 2e-3,
                                 .simulator_default = 2e-4,
                                 .may_be_zero = true,
                                 .differentiable = false},
    .family = Family::rate,
    .c_form = {.expression = "(rate > {theta} ? 1.0 : (rate < -{theta} ? -1.0 : 0.0))"},
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double dead_band) {
      const double r = s.rate_c_per_s[p];
      return r > dead_band ? 1.0 : (r < -dead_band ? -1.0 : 0.0);
    })>,
};

}  // namespace gyrotherm::effects
