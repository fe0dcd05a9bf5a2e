// dT: r = dT/dt (°C/s), the temperature-rate effect (the cavity bends and
// the discharge's gas flow shifts while the block heats or cools); the
// paper's b3, [truth] b3_dph_per_c_per_s.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_rate{
    .name = "dT", .meaning = "temperature-rate effect (cavity bending, gas flow)", .unit = "°C/s",
    .truth_key = "b3_dph_per_c_per_s", .family = Family::rate, .c_form = {"rate"},
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) { return s.rate_c_per_s[p]; })>};

}  // namespace gyrotherm::effects
