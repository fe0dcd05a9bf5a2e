#include "fit/data/sensor_kind.h"

#include <fmt/format.h>

#include "fit/data/column_role.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

#define SENSOR_KIND(name) &name##_sensor(),
const SensorKind* const kKinds[] = {
#include "fit/data/sensor_kinds.def"
};
#undef SENSOR_KIND

}  // namespace

std::span<const SensorKind* const> sensor_kinds() { return kKinds; }

std::string sensor_kind_names() {
  std::string out;
  for (std::size_t k = 0; k < std::size(kKinds); ++k)
    out += std::string(k == 0 ? "" : k + 1 == std::size(kKinds) ? " or " : ", ") + std::string(kKinds[k]->name);
  return out;
}

bool names_sensor(std::string_view name, const SensorKind& kind) {
  bool named = false;
  for (const std::string& word : column_words(name)) {
    if (word.starts_with("temp")) return false;
    std::string_view prefixes = kind.words;
    while (!prefixes.empty()) {
      const std::size_t space = prefixes.find(' ');
      if (word.starts_with(prefixes.substr(0, space))) named = true;
      if (space == std::string_view::npos) break;
      prefixes.remove_prefix(space + 1);
    }
  }
  return named;
}

const SensorKind& sensor_kind(std::string_view name) {
  if (name.empty()) return *kKinds[0];
  for (const SensorKind* k : kKinds)
    if (k->name == name) return *k;
  throw InputError(fmt::format("--sensor '{}': must be {}", name, sensor_kind_names()));
}

}  // namespace gyrotherm::fit
