// T^3: r = T³ (°C³), higher-order curvature of the temperature sensitivity
// (a hidden effect: [hidden] T^3 = COEF).
#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

void regressor(const EffectSeries& s, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.temp_c[p] * s.temp_c[p] * s.temp_c[p];
}

}  // namespace

extern constinit const Effect temperature_cubed{
    .name = "T^3",
    .meaning = "higher-order curvature",
    .unit = "°C³",
    .regressor = &regressor,
};

}  // namespace gyrotherm::effects
