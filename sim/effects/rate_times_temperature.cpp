// T*dT: r = T·dT/dt (°C²/s), a rate sensitivity that changes with
// temperature.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect rate_times_temperature{
    .name = "T*dT", .meaning = "rate sensitivity that changes with temperature", .unit = "°C²/s",
    .family = Family::rate, .c_form = {"T * rate"},
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) { return s.temp_c[p] * s.rate_c_per_s[p]; })>};

}  // namespace gyrotherm::effects
