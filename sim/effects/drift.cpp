// t: r = hours since the start of the record, a slow drift (ageing).
#include "sim/effects/effect.h"

namespace gyrotherm::effects {
namespace {

void regressor(const EffectSeries& s, double, std::span<double> out) {
  for (std::size_t p = 0; p < out.size(); ++p) out[p] = s.time_s[p] / 3600.0;
}

}  // namespace

extern constinit const Effect drift{
    .name = "t",
    .meaning = "slow drift, ageing",
    .unit = "h",
    .columns = kTime,
    .regressor = &regressor,
};

}  // namespace gyrotherm::effects
