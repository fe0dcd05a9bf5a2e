// dT: r = dT/dt (°C/s), the temperature-rate effect (the cavity bends and
// the discharge's gas flow shifts while the block heats or cools); the
// paper's b3, [truth] b3_dph_per_c_per_s.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

void regressor(const EffectSeries& s, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.rate_c_per_s[p];
}

}  // namespace

extern constinit const Effect temperature_rate{
    .name = "dT",
    .meaning = "temperature-rate effect (cavity bending, gas flow)",
    .unit = "°C/s",
    .truth_key = "b3_dph_per_c_per_s",
    .regressor = &regressor,
};

}  // namespace gyrotherm::effects
