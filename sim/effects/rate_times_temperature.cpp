// T*dT: r = T·dT/dt (°C²/s), a rate sensitivity that changes with
// temperature.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

void regressor(const EffectSeries& s, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.temp_c[p] * s.rate_c_per_s[p];
}

}  // namespace

extern constinit const Effect rate_times_temperature{
    .name = "T*dT",
    .meaning = "rate sensitivity that changes with temperature",
    .unit = "°C²/s",
    .regressor = &regressor,
};

}  // namespace gyrotherm::effects
