// T^3: r = T³ (°C³), higher-order curvature of the temperature sensitivity
// (a hidden effect: [hidden] T^3 = COEF).
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_cubed = power_of_temperature<3>(
    {.name = "T^3", .meaning = "higher-order curvature", .unit = "°C³", .c_form = {"T * T * T"}});

}  // namespace gyrotherm::effects
