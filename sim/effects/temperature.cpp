// T: the gyro temperature itself, r = T (°C). Its true coefficient is the
// paper's b1, the gyro file's [truth] b1_dph_per_c.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature = power_of_temperature<1>(
    {.name = "T", .meaning = "temperature sensitivity", .unit = "°C", .truth_key = "b1_dph_per_c", .c_form = {"T"}});

}  // namespace gyrotherm::effects
