#include "sim/channel.h"

namespace gyrotherm::sim {
namespace {

// The CSV suffixes are the ones the log reader takes as these units
// (fit/data/units.cpp): dph, mps2, pa.
constexpr ChannelKind kKinds[] = {
    {"gyro", "°/h", "dph", true},
    {"accel", "m/s²", "mps2", true},
    {"baro", "Pa", "pa", false},
};

}  // namespace

const ChannelKind* find_channel_kind(std::string_view name) {
  for (const ChannelKind& k : kKinds)
    if (k.name == name) return &k;
  return nullptr;
}

std::string channel_kind_names() {
  std::string out;
  for (std::size_t k = 0; k < std::size(kKinds); ++k)
    out += std::string(k == 0 ? "" : k + 1 == std::size(kKinds) ? " or " : ", ") + std::string(kKinds[k].name);
  return out;
}

std::map<std::string, double> ChannelConfig::true_coefficients() const {
  std::map<std::string, double> truth = {{"1", b0}};
  for (const auto& [term, c] : coefficient)
    if (c != 0.0) truth[term] = c;
  return truth;
}

std::string ChannelConfig::label() const {
  return kind->has_axes ? std::string(kind->name) + " " + axis : std::string(kind->name);
}

// accel_x, baro: the kind and its axis, before the unit's suffix.
std::string ChannelConfig::stem() const {
  return std::string(kind->name) + (kind->has_axes ? std::string("_") + axis : "");
}

std::string ChannelConfig::column() const { return stem() + "_" + std::string(kind->suffix); }

std::string ChannelConfig::truth_column() const { return stem() + "_true_" + std::string(kind->suffix); }

}  // namespace gyrotherm::sim
