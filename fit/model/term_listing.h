#pragma once
// `gyrotherm effects`: the effect registry (sim/effects/effect.h) listed for
// people and as JSON ({"effects": [{term, meaning, unit, needs, columns,
// coefficient_unit, simulator, parameter?}]}).

#include <nlohmann/json_fwd.hpp>
#include <string>

namespace gyrotherm::fit {

nlohmann::ordered_json effects_json();
std::string effects_text();

}  // namespace gyrotherm::fit
