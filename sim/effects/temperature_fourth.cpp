// T^4: r = T⁴ (°C⁴), a fourth-order term of the temperature sensitivity, for
// gyros whose bias curve a cubic does not follow over a wide range (a hidden
// effect: [hidden] T^4 = COEF). PX4 and ArduPilot store cubics: their exports
// refuse it.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_fourth = power_of_temperature<4>(
    {.name = "T^4", .meaning = "fourth-order curvature", .unit = "°C⁴", .c_form = {"T * T * T * T"}});

}  // namespace gyrotherm::effects
