#include "fit/engines/engine_listing.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "fit/engines/engine.h"

namespace gyrotherm::fit {

nlohmann::ordered_json engines_json() {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (const EngineInfo& e : engine_registry()) {
    nlohmann::ordered_json options = nlohmann::ordered_json::object();
    for (const OptionInfo& o : e.options) options[o.keyword] = option_line(o);
    j.push_back({{"name", e.name},
                 {"description", e.description},
                 {"stochastic", e.stochastic},
                 {"default_evaluations", e.default_evaluations},
                 {"options", options}});
  }
  return nlohmann::ordered_json{{"engines", j}};
}

std::string engines_text() {
  std::string out;
  for (const EngineInfo& e : engine_registry()) {
    out += fmt::format("{:<9} {}{}\n", e.name, e.description, e.stochastic ? " [seeded]" : "");
    for (const OptionInfo& o : e.options) out += fmt::format("          --option {}=  {}\n", o.keyword, option_line(o));
  }
  return out;
}

}  // namespace gyrotherm::fit
