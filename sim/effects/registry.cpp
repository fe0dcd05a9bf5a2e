// The registry of sim/effects/effect.h, built from sim/effects/registry.def.

#include "sim/effects/effect.h"

namespace gyrotherm::effects {

#define EFFECT(x) extern const Effect x;
#include "sim/effects/registry.def"
#undef EFFECT

const std::vector<const Effect*>& registry() {
  static const std::vector<const Effect*> all = {
#define EFFECT(x) &x,
#include "sim/effects/registry.def"
#undef EFFECT
  };
  return all;
}

const Effect* find(std::string_view name) {
  for (const Effect* e : registry())
    if (e->name == name) return e;
  return nullptr;
}

const Effect* find_by_truth_key(std::string_view truth_key) {
  for (const Effect* e : registry())
    if (!e->truth_key.empty() && e->truth_key == truth_key) return e;
  return nullptr;
}

namespace {
std::string join(bool hidden_only) {
  std::string out;
  for (const Effect* e : registry())
    if (!hidden_only || e->hidden()) out += (out.empty() ? "" : ", ") + std::string(e->name);
  return out;
}
}  // namespace

std::string names() { return join(false); }
std::string hidden_names() { return join(true); }

std::string Effect::coefficient_unit(std::string_view measured) const {
  return unit == "1" ? std::string(measured) : std::string(measured) + " per " + std::string(unit);
}

std::string Effect::column_names() const {
  std::string out;
  auto add = [&](unsigned bit, const char* column_name) {
    if ((columns & bit) != 0) out += (out.empty() ? "" : ", ") + std::string(column_name);
  };
  add(kTime, "time_s");
  add(kTemp, "temp_c");
  add(kTemp2, "temp2_c");
  return out;
}

std::vector<double> regressor_values(const Effect& effect, const EffectSeries& series,
                                     double parameter) {
  std::vector<double> r(series.size());
  effect.compute(series, parameter, r);
  return r;
}

}  // namespace gyrotherm::effects
