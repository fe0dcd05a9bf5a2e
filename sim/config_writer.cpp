#include "sim/config_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <utility>

#include "sim/effects/effect.h"
#include "sim/util/input_error.h"

namespace gyrotherm::sim {
namespace {

// A double as the shortest decimal that parses back to it; a whole number
// keeps a ".0" so that TOML reads a float ("7200.0", not the integer 7200).
std::string shortest(double v) {
  assert(std::isfinite(v));  // the loader refuses anything else
  std::string text = fmt::format("{}", v);
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

// A TOML basic string: quotes, backslashes and control characters escaped,
// everything else (UTF-8 included) as it is.
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      out += fmt::format("\\u{:04X}", static_cast<unsigned>(u));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A key as it is when bare (A–Z, a–z, 0–9, _ and -), else quoted ("T^3").
std::string key(std::string_view k) {
  for (const char c : k)
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-'))
      return quoted(k);
  return std::string(k);
}

// The lines of a file: the header as comments, then tables of `key = value`.
class TomlText {
 public:
  explicit TomlText(std::string_view header) {
    while (!header.empty() && header.back() == '\n') header.remove_suffix(1);
    std::size_t from = 0;
    while (!header.empty() && from <= header.size()) {
      const std::size_t end = std::min(header.find('\n', from), header.size());
      const std::string_view line = header.substr(from, end - from);
      text_ += line.empty() ? "#\n" : fmt::format("# {}\n", line);
      from = end + 1;
    }
  }
  // "[name]", then `key = number` for each of `numbers`.
  void table(std::string_view name, std::initializer_list<std::pair<std::string_view, double>> numbers = {}) {
    text_ += fmt::format("\n[{}]\n", name);
    for (const auto& [k, v] : numbers) number(k, v);
  }
  void value(std::string_view k, std::string_view written, std::string_view comment = {}) {
    text_ += fmt::format("{} = {}", key(k), written);
    if (!comment.empty()) text_ += fmt::format("  # {}", comment);
    text_ += '\n';
  }
  void number(std::string_view k, double v, std::string_view comment = {}) {
    value(k, shortest(v), comment);
  }
  void boolean(std::string_view k, bool v) { value(k, v ? "true" : "false"); }
  void string(std::string_view k, std::string_view v) { value(k, quoted(v)); }
  void raw(std::string_view line) { text_ += line; }
  std::string take() { return std::move(text_); }

 private:
  std::string text_;
};

}  // namespace

std::string gyro_toml(const GyroConfig& gyro, std::string_view header) {
  TomlText t(header);
  t.table("truth");
  t.number("b0_dph", gyro.b0_dph, "°/h");
  for (const effects::Effect* e : effects::registry())
    if (!e->hidden()) t.number(e->truth_key, gyro.coefficient_of(*e), e->coefficient_unit());

  bool hidden_table = !gyro.parameter.empty();
  for (const auto& [name, value] : gyro.coefficient) {
    const effects::Effect* e = effects::find(name);
    assert(e != nullptr);  // coefficients are by term name of the registry
    if (e != nullptr && e->hidden()) hidden_table = true;
  }
  if (hidden_table) {
    t.table("hidden");
    for (const effects::Effect* e : effects::registry())
      if (e->hidden())
        t.number(e->name, gyro.coefficient_of(*e), fmt::format("{}: {}", e->coefficient_unit(), e->meaning));
    for (const effects::Effect* e : effects::registry())
      if (e->parameter)
        t.number(e->parameter->gyro_key, gyro.parameter_of(*e), fmt::format("{}'s {}", e->name, e->parameter->name));
  }

  const NoiseConfig& n = gyro.noise;
  t.table("noise");
  t.number("arw_deg_per_sqrt_h", n.arw_deg_per_sqrt_h, "°/√h");
  t.number("bias_instability_dph", n.bias_instability_dph, "°/h, the flicker floor of the Allan deviation");
  t.number("flicker_tau_min_s", n.flicker_tau_min_s);
  t.number("flicker_tau_max_s", n.flicker_tau_max_s);
  t.value("flicker_processes", fmt::format("{}", n.flicker_processes));
  t.number("rrw_dph_per_sqrt_h", n.rrw_dph_per_sqrt_h, "°/h/√h");
  t.number("quantization_arcsec", n.quantization_arcsec, "0 = off");
  t.number("glitch_rate_per_h", n.glitch_rate_per_h, "0 = off");
  t.number("glitch_size_dph", n.glitch_size_dph);
  t.number("arw_temp_ref_c", n.arw_temp_ref_c);
  t.number("arw_temp_coeff_per_c2", n.arw_temp_coeff_per_c2, "white noise × (1 + k·(T − T_ref)²)");
  for (const ChannelConfig& ch : gyro.channels) {
    t.raw("\n[[channel]]\n");
    t.string("sensor", ch.kind->name);
    if (ch.kind->has_axes) t.string("axis", std::string(1, ch.axis));
    t.number("b0", ch.b0, ch.kind->unit);
    t.number("white_noise", ch.white_noise, fmt::format("{}·√s", ch.kind->unit));
    if (ch.coefficient.empty()) continue;
    t.raw("[channel.terms]\n");
    for (const auto& [term, c] : ch.coefficient) t.number(term, c);
  }
  return t.take();
}

std::string rig_toml(const RigConfig& rig, std::string_view header) {
  TomlText t(header);
  const ChamberConfig& ch = rig.chamber;
  t.table("chamber", {{"capacity_j_per_k", ch.capacity_j_per_k}, {"insulation_w_per_k", ch.insulation_w_per_k},
                      {"heater_max_w", ch.heater_max_w}, {"cooler_max_w", ch.cooler_max_w},
                      {"kp_w_per_k", ch.kp_w_per_k}, {"ti_s", ch.ti_s}, {"feedforward_j_per_k", ch.feedforward_j_per_k},
                      {"min_c", ch.min_c}, {"max_c", ch.max_c}});
  const CaseConfig& cs = rig.case_;
  t.table("case", {{"capacity_j_per_k", cs.capacity_j_per_k}, {"convection_w_per_k", cs.convection_w_per_k},
                   {"emissivity", cs.emissivity}, {"area_m2", cs.area_m2}});
  t.boolean("natural_convection", cs.natural_convection);
  const BlockConfig& b = rig.block;
  t.table("block", {{"anode_capacity_j_per_k", b.anode_capacity_j_per_k},
                    {"far_capacity_j_per_k", b.far_capacity_j_per_k}, {"anode_far_w_per_k", b.anode_far_w_per_k},
                    {"anode_case_w_per_k", b.anode_case_w_per_k}, {"far_case_w_per_k", b.far_case_w_per_k}});
  const SensorConfig& s = rig.sensor;
  t.table("sensor", {{"time_constant_s", s.time_constant_s}, {"noise_c", s.noise_c}, {"resolution_c", s.resolution_c}});
  const PowerConfig& p = rig.power;
  t.table("power", {{"discharge_w", p.discharge_w}, {"dither_w", p.dither_w}, {"electronics_w", p.electronics_w}});
  return t.take();
}

std::string scenario_toml(const Scenario& scenario, std::string_view rig_file, std::string_view gyro_file,
                          std::string_view header) {
  if (scenario.seed > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    throw InputError(fmt::format("seed {}: a scenario file holds seeds up to {} (a TOML integer)", scenario.seed,
                                 std::numeric_limits<std::int64_t>::max()));
  TomlText t(header);
  t.raw("\n");
  t.string("name", scenario.name);
  t.string("description", scenario.description);
  t.string("rig", rig_file);
  t.string("gyro", gyro_file);
  t.value("seed", fmt::format("{}", scenario.seed));
  t.number("sample_rate_hz", scenario.sample_rate_hz);
  t.number("room_c", scenario.room_c);
  t.boolean("chamber", scenario.chamber);
  if (scenario.chamber) t.number("start_c", scenario.start_c);  // without a chamber it is room_c
  t.string("initial", scenario.initial == InitialCondition::steady ? "steady" : "soaked");
  for (const Segment& s : scenario.segments) {
    t.raw("\n[[segment]]\n");
    t.string("kind", to_string(s.kind));
    switch (s.kind) {
      case SegmentKind::hold:
        t.number("temp_c", s.temp_c);
        t.number("duration_s", s.duration_s);
        break;
      case SegmentKind::ramp:
        t.number("target_c", s.temp_c);
        t.number("rate_c_per_min", s.rate_c_per_min);
        break;
      case SegmentKind::free:
        t.number("duration_s", s.duration_s);
        break;
    }
  }
  if (!scenario.spread.empty()) {
    t.table("spread");
    for (const auto& [k, relative] : scenario.spread) t.number(k, relative);
  }
  return t.take();
}

}  // namespace gyrotherm::sim
