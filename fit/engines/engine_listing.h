#pragma once
// `gyrotherm engines`: the engine registry (fit/engines/engine.h) listed for
// people and as JSON ({"engines": [{name, description, stochastic,
// default_evaluations, options: {KEY: rule}}]}).

#include <nlohmann/json_fwd.hpp>
#include <string>

namespace gyrotherm::fit {

nlohmann::ordered_json engines_json();
std::string engines_text();

}  // namespace gyrotherm::fit
