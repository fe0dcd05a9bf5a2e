// t: r = hours since the start of the record, a slow drift (ageing).
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect drift{
    .name = "t", .meaning = "slow drift, ageing", .unit = "h", .columns = kTime, .family = Family::time,
    .c_form = {"rel / 3600.0"},
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) { return s.time_s[p] / 3600.0; })>};

}  // namespace gyrotherm::effects
