// T^2: r = T² (°C²), the curvature of the temperature sensitivity; the
// paper's b2, [truth] b2_dph_per_c2.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

void regressor(const EffectSeries& s, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.temp_c[p] * s.temp_c[p];
}

}  // namespace

extern constinit const Effect temperature_squared{
    .name = "T^2",
    .meaning = "curvature of the sensitivity",
    .unit = "°C²",
    .truth_key = "b2_dph_per_c2",
    .regressor = &regressor,
};

}  // namespace gyrotherm::effects
