// grad: r = T₂ − T (°C), the temperature difference across the gyro block
// between the far-side sensor and the anode-side one: an imbalance of the
// Langmuir flow in the two discharge legs. Needs the temp2_c column.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect gradient{
    .name = "grad", .meaning = "temperature gradient across the block (Langmuir-flow imbalance)", .unit = "°C",
    .columns = kTemp | kTemp2, .family = Family::gradient, .c_form = {"T2 - T"},
    .regressor = pointwise<([](const EffectSeries& s, std::size_t p, double) { return s.temp2_c[p] - s.temp_c[p]; })>};

}  // namespace gyrotherm::effects
