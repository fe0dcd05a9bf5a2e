// T: the gyro temperature itself, r = T (°C). Its true coefficient is the
// paper's b1, the gyro file's [truth] b1_dph_per_c.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

void regressor(const EffectSeries& s, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.temp_c[p];
}

}  // namespace

extern constinit const Effect temperature{
    .name = "T",
    .meaning = "temperature sensitivity",
    .unit = "°C",
    .truth_key = "b1_dph_per_c",
    .regressor = &regressor,
};

}  // namespace gyrotherm::effects
