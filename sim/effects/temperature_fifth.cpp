// T^5: r = T⁵ (°C⁵), a fifth-order term of the temperature sensitivity: the
// fifth-order fits one MEMS gyro family needs over a wide range (a hidden
// effect: [hidden] T^5 = COEF). PX4 and ArduPilot store cubics: their exports
// refuse it.
#include "sim/effects/effect.h"

namespace gyrotherm::effects {

extern constinit const Effect temperature_fifth = power_of_temperature<5>(
    {.name = "T^5", .meaning = "fifth-order curvature", .unit = "°C⁵", .c_form = {"T * T * T * T * T"}});

}  // namespace gyrotherm::effects
