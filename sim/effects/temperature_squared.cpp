// T^2: r = T² (°C²), the curvature of the temperature sensitivity; the
// paper's b2, [truth] b2_dph_per_c2.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_squared = power_of_temperature<2>({.name = "T^2",
    .meaning = "curvature of the sensitivity", .unit = "°C²", .truth_key = "b2_dph_per_c2", .c_form = {"T * T"}});

}  // namespace gyrotherm::effects
