#include "fit/model/term_listing.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sim/effects/effect.h"

namespace gyrotherm::fit {

nlohmann::ordered_json effects_json() {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (const effects::Effect* t : effects::registry()) {
    nlohmann::ordered_json e = {{"term", t->name},
                                {"meaning", t->meaning},
                                {"unit", t->unit},
                                {"needs", t->needs_temp2() ? "temp2_c" : "temp_c"},
                                {"columns", t->column_names()},
                                {"coefficient_unit", t->coefficient_unit()},
                                {"simulator", t->hidden() ? "[hidden] " + std::string(t->name)
                                                          : "[truth] " + std::string(t->truth_key)}};
    if (t->parameter)
      e["parameter"] = {{"name", t->parameter->name},
                        {"lower", t->parameter->lower},
                        {"upper", t->parameter->upper},
                        {"gyro_key", t->parameter->gyro_key},
                        {"simulator_default", t->parameter->simulator_default}};
    j.push_back(e);
  }
  return nlohmann::ordered_json{{"effects", j}};
}

std::string effects_text() {
  std::string out;
  for (const effects::Effect* t : effects::registry()) {
    std::string extra = t->needs_temp2() ? "  (needs temp2_c)" : "";
    if (t->parameter)
      extra += fmt::format("  ({} fitted in [{:g}, {:g}])", t->parameter->name, t->parameter->lower, t->parameter->upper);
    out += fmt::format("{:<7} {:<8} {}{}\n", t->name, t->unit, t->meaning, extra);
  }
  out += fmt::format("\nSimulate a hidden effect with 'gyrotherm simulate ... --hidden TERM=COEF' (TERM one of "
                     "{}); its parameter, if any, is set in the gyro file's [hidden] table.\n",
                     effects::hidden_names());
  return out;
}

}  // namespace gyrotherm::fit
