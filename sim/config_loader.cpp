#include "sim/config_loader.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <charconv>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "sim/effects/effect.h"
#include "sim/util/input_error.h"

namespace gyrotherm::sim {
namespace {

enum class Rule { any, positive, non_negative, unit_interval, relative_spread };

const char* describe(Rule rule) {
  switch (rule) {
    case Rule::any: return "";
    case Rule::positive: return "must be > 0";
    case Rule::non_negative: return "must be >= 0";
    case Rule::unit_interval: return "must be between 0 and 1";
    case Rule::relative_spread:
      return "must be >= 0 and < 1 (a relative half-width: 0.1 means ±10 %)";
  }
  return "";
}

bool satisfies(double v, Rule rule) {
  switch (rule) {
    case Rule::any: return true;
    case Rule::positive: return v > 0.0;
    case Rule::non_negative: return v >= 0.0;
    case Rule::unit_interval: return v >= 0.0 && v <= 1.0;
    case Rule::relative_spread: return v >= 0.0 && v < 1.0;
  }
  return true;
}

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
  }
}

toml::table parse(const std::filesystem::path& file) {
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    throw InputError(file.string() + ": no such file");
  if (std::filesystem::is_directory(file, error))
    throw InputError(file.string() + ": is a folder, expected a TOML file");
  try {
    return toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw InputError(located(file.string(), e.source().begin.line,
                             "not valid TOML: " + std::string(e.description())));
  }
}

// Reads the keys of one table, remembers which were used, and reports the
// rest as unknown.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string prefix)
      : table_(table), file_(std::move(file)), prefix_(std::move(prefix)) {}

  std::string key_path(std::string_view key) const {
    return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
  }

  [[noreturn]] void fail(const toml::node& node, const std::string& message) const {
    throw InputError(located(file_, node.source().begin.line, message));
  }
  [[noreturn]] void fail_here(const std::string& message) const {
    throw InputError(located(file_, table_.source().begin.line, message));
  }

  const toml::node* find(std::string_view key) {
    known_.insert(std::string(key));
    return table_.get(key);
  }

  bool has(std::string_view key) const { return table_.contains(key); }

  void number(std::string_view key, double& out, Rule rule = Rule::any) {
    const toml::node* node = find(key);
    if (node == nullptr) return;
    if (!node->is_number())
      fail(*node, key_path(key) + ": expected a number, found " + type_name(*node));
    const double v = node->value<double>().value_or(0.0);
    if (!std::isfinite(v)) fail(*node, key_path(key) + ": must be a finite number");
    if (!satisfies(v, rule))
      fail(*node, key_path(key) + " = " + format(v) + ": " + describe(rule));
    out = v;
  }

  void integer(std::string_view key, int& out, int min_value, int max_value) {
    const toml::node* node = find(key);
    if (node == nullptr) return;
    if (!node->is_integer())
      fail(*node, key_path(key) + ": expected an integer, found " + type_name(*node));
    const std::int64_t v = node->value<std::int64_t>().value_or(0);
    if (v < min_value || v > max_value)
      fail(*node, key_path(key) + " = " + std::to_string(v) + ": must be between " +
                      std::to_string(min_value) + " and " + std::to_string(max_value));
    out = static_cast<int>(v);
  }

  void seed(std::string_view key, std::uint64_t& out) {
    const toml::node* node = find(key);
    if (node == nullptr) return;
    if (!node->is_integer())
      fail(*node, key_path(key) + ": expected a non-negative integer, found " + type_name(*node));
    const std::int64_t v = node->value<std::int64_t>().value_or(0);
    if (v < 0) fail(*node, key_path(key) + " = " + std::to_string(v) + ": must be >= 0");
    out = static_cast<std::uint64_t>(v);
  }

  void boolean(std::string_view key, bool& out) {
    const toml::node* node = find(key);
    if (node == nullptr) return;
    if (!node->is_boolean())
      fail(*node, key_path(key) + ": expected true or false, found " + type_name(*node));
    out = node->value<bool>().value_or(false);
  }

  void string(std::string_view key, std::string& out) {
    const toml::node* node = find(key);
    if (node == nullptr) return;
    if (!node->is_string())
      fail(*node, key_path(key) + ": expected a string, found " + type_name(*node));
    out = node->value<std::string>().value_or("");
  }

  // A sub-table; nullptr when absent.
  const toml::table* table(std::string_view key) {
    const toml::node* node = find(key);
    if (node == nullptr) return nullptr;
    if (!node->is_table())
      fail(*node, key_path(key) + ": expected a table [" + key_path(key) + "], found " +
                      type_name(*node));
    return node->as_table();
  }

  // The sub-table `key`, if there: read(reader) reads its keys, then any other
  // key in it is refused.
  template <class Read>
  void section(std::string_view key, Read read) {
    if (const toml::table* t = table(key)) {
      TableReader c(*t, file_, key_path(key));
      read(c);
      c.finish();
    }
  }

  // Every key that was not asked for is an error listing the known ones.
  void finish(const std::string& known_list = "") const {
    for (auto&& [key, node] : table_) {
      if (known_.count(std::string(key.str())) != 0) continue;
      std::string list = known_list;
      if (list.empty())
        for (const std::string& k : known_) list += (list.empty() ? "" : ", ") + k;
      const std::string where = prefix_.empty() ? "at the top level" : "in [" + prefix_ + "]";
      throw InputError(located(file_, key.source().begin.line,
                               "unknown key '" + key_path(key.str()) + "' " + where +
                                   " (known keys: " + list + ")"));
    }
  }

  static std::string format(double v) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, result.ptr);
  }

  const std::string& file() const { return file_; }
  const toml::table& raw() const { return table_; }

 private:
  const toml::table& table_;
  std::string file_;
  std::string prefix_;
  std::set<std::string> known_;
};

// One of duration_s / duration_min / duration_h, exactly one, > 0.
double read_duration(TableReader& r, const std::string& what) {
  double seconds = 0.0;
  int found = 0;
  const std::pair<const char*, double> units[] = {
      {"duration_s", 1.0}, {"duration_min", 60.0}, {"duration_h", 3600.0}};
  for (const auto& [key, scale] : units) {
    if (!r.has(key)) {
      r.find(key);
      continue;
    }
    double v = 0.0;
    r.number(key, v, Rule::positive);
    seconds = v * scale;
    ++found;
  }
  if (found != 1)
    r.fail_here(what + ": give exactly one of duration_s, duration_min, duration_h (> 0)");
  return seconds;
}

std::filesystem::path relative_to(const std::filesystem::path& base_file, const std::string& p) {
  const std::filesystem::path path(p);
  if (path.is_absolute()) return path;
  return base_file.parent_path() / path;
}

}  // namespace

Scenario load_scenario(const std::filesystem::path& file) {
  const toml::table root = parse(file);
  TableReader r(root, file.string(), "");
  Scenario s;
  s.file = file;
  s.name = file.stem().string();
  r.string("name", s.name);
  r.string("description", s.description);
  std::string rig = "rig.toml", gyro = "gyro.toml";
  r.string("rig", rig);
  r.string("gyro", gyro);
  s.rig_file = relative_to(file, rig);
  s.gyro_file = relative_to(file, gyro);
  r.seed("seed", s.seed);
  r.number("sample_rate_hz", s.sample_rate_hz, Rule::positive);
  if (s.sample_rate_hz > 1000.0)
    r.fail(*r.find("sample_rate_hz"), "sample_rate_hz: at most 1000 Hz");
  r.number("room_c", s.room_c);
  if (s.room_c < -50.0 || s.room_c > 60.0)
    r.fail(*r.find("room_c"), "room_c = " + TableReader::format(s.room_c) +
                                  ": a room between -50 and 60 °C was expected");
  r.boolean("chamber", s.chamber);
  s.start_c = s.room_c;
  r.number("start_c", s.start_c);
  std::string initial = "soaked";
  r.string("initial", initial);
  if (initial == "soaked")
    s.initial = InitialCondition::soaked;
  else if (initial == "steady")
    s.initial = InitialCondition::steady;
  else
    r.fail(*r.find("initial"), "initial = \"" + initial + "\": expected \"soaked\" or \"steady\"");

  const toml::node* segments = r.find("segment");
  if (segments == nullptr || !segments->is_array_of_tables() || segments->as_array()->empty())
    throw InputError(located(file.string(), segments ? segments->source().begin.line : 0,
                             "expected at least one [[segment]] (kind = \"hold\", \"ramp\" or "
                             "\"free\")"));
  std::size_t index = 0;
  for (const toml::node& node : *segments->as_array()) {
    ++index;
    const std::string what = "segment " + std::to_string(index);
    TableReader seg(*node.as_table(), file.string(), what);
    Segment segment;
    segment.source_line = node.source().begin.line;
    std::string kind;
    seg.string("kind", kind);
    if (kind == "hold") {
      segment.kind = SegmentKind::hold;
      if (!seg.has("temp_c")) seg.fail_here(what + ": a hold needs temp_c");
      seg.number("temp_c", segment.temp_c);
      segment.duration_s = read_duration(seg, what);
    } else if (kind == "ramp") {
      segment.kind = SegmentKind::ramp;
      if (!seg.has("target_c")) seg.fail_here(what + ": a ramp needs target_c");
      if (!seg.has("rate_c_per_min")) seg.fail_here(what + ": a ramp needs rate_c_per_min");
      seg.number("target_c", segment.temp_c);
      seg.number("rate_c_per_min", segment.rate_c_per_min, Rule::positive);
    } else if (kind == "free") {
      segment.kind = SegmentKind::free;
      segment.duration_s = read_duration(seg, what);
    } else {
      seg.fail_here(what + ": kind = \"" + kind + "\": expected \"hold\", \"ramp\" or \"free\"");
    }
    seg.finish();
    if (!s.chamber && segment.kind != SegmentKind::free)
      seg.fail_here(what + ": chamber = false, so there is no set point to " +
                    (segment.kind == SegmentKind::hold ? "hold" : "ramp") +
                    "; use kind = \"free\"");
    s.segments.push_back(segment);
  }
  // [spread]: per-trial relative ranges for `gyrotherm score` (sim/scenario.h).
  if (const toml::table* t = r.table("spread")) {
    TableReader c(*t, file.string(), "spread");
    for (const std::string_view key : kSpreadKeys) {
      double relative = 0.0;
      if (!c.has(key)) {
        c.find(key);  // known, absent
        continue;
      }
      c.number(key, relative, Rule::relative_spread);
      s.spread[std::string(key)] = relative;
    }
    std::string known;
    for (const std::string_view key : kSpreadKeys) known += (known.empty() ? "" : ", ") + std::string(key);
    c.finish(known);
  }
  r.finish();
  if (!s.chamber) s.start_c = s.room_c;
  return s;
}

RigConfig load_rig(const std::filesystem::path& file) {
  const toml::table root = parse(file);
  TableReader r(root, file.string(), "");
  RigConfig rig;
  r.section("chamber", [&](TableReader& c) {
    ChamberConfig& ch = rig.chamber;
    c.number("capacity_j_per_k", ch.capacity_j_per_k, Rule::positive);
    c.number("insulation_w_per_k", ch.insulation_w_per_k, Rule::non_negative);
    c.number("heater_max_w", ch.heater_max_w, Rule::non_negative);
    c.number("cooler_max_w", ch.cooler_max_w, Rule::non_negative);
    c.number("kp_w_per_k", ch.kp_w_per_k, Rule::positive);
    c.number("ti_s", ch.ti_s, Rule::positive);
    c.number("feedforward_j_per_k", ch.feedforward_j_per_k, Rule::non_negative);
    c.number("min_c", ch.min_c);
    c.number("max_c", ch.max_c);
    if (ch.min_c >= ch.max_c) c.fail_here("chamber.min_c must be below chamber.max_c");
  });
  r.section("case", [&](TableReader& c) {
    CaseConfig& cs = rig.case_;
    c.number("capacity_j_per_k", cs.capacity_j_per_k, Rule::positive);
    c.number("convection_w_per_k", cs.convection_w_per_k, Rule::non_negative);
    c.boolean("natural_convection", cs.natural_convection);
    c.number("emissivity", cs.emissivity, Rule::unit_interval);
    c.number("area_m2", cs.area_m2, Rule::non_negative);
  });
  r.section("block", [&](TableReader& c) {
    BlockConfig& b = rig.block;
    c.number("anode_capacity_j_per_k", b.anode_capacity_j_per_k, Rule::positive);
    c.number("far_capacity_j_per_k", b.far_capacity_j_per_k, Rule::positive);
    c.number("anode_far_w_per_k", b.anode_far_w_per_k, Rule::non_negative);
    c.number("anode_case_w_per_k", b.anode_case_w_per_k, Rule::non_negative);
    c.number("far_case_w_per_k", b.far_case_w_per_k, Rule::non_negative);
    if (b.anode_case_w_per_k + b.far_case_w_per_k <= 0.0)
      c.fail_here("block: anode_case_w_per_k and far_case_w_per_k cannot both be 0 (the block "
                  "would never exchange heat with the case)");
  });
  r.section("sensor", [&](TableReader& c) {
    SensorConfig& s = rig.sensor;
    c.number("time_constant_s", s.time_constant_s, Rule::positive);
    c.number("noise_c", s.noise_c, Rule::non_negative);
    c.number("resolution_c", s.resolution_c, Rule::non_negative);
  });
  r.section("power", [&](TableReader& c) {
    PowerConfig& p = rig.power;
    c.number("discharge_w", p.discharge_w, Rule::non_negative);
    c.number("dither_w", p.dither_w, Rule::non_negative);
    c.number("electronics_w", p.electronics_w, Rule::non_negative);
  });
  r.finish();
  return rig;
}

// [[channel]]: sensor, axis (none for a kind without axes), b0, white_noise
// and [channel.terms] (coefficients by term name); sim/channel.h.
std::vector<ChannelConfig> read_channels(TableReader& r) {
  std::vector<ChannelConfig> channels;
  const toml::node* list = r.find("channel");
  if (list == nullptr) return channels;
  if (!list->is_array_of_tables()) r.fail(*list, "channel: expected [[channel]] tables, found " + type_name(*list));
  for (const toml::node& node : *list->as_array()) {
    const std::string what = "channel " + std::to_string(channels.size() + 1);
    TableReader c(*node.as_table(), r.file(), what);
    ChannelConfig ch;
    ch.line = static_cast<int>(node.source().begin.line);
    std::string sensor, axis;
    c.string("sensor", sensor);
    ch.kind = find_channel_kind(sensor);
    if (ch.kind == nullptr)
      c.fail_here(what + ": sensor = \"" + sensor + "\": expected " + channel_kind_names());
    c.string("axis", axis);
    if (ch.kind->has_axes && (axis.size() != 1 || axis.find_first_of("xyz") != 0))
      c.fail_here(what + ": sensor = \"" + sensor + "\" needs axis = \"x\", \"y\" or \"z\"");
    if (!ch.kind->has_axes && c.has("axis")) c.fail_here(what + ": sensor = \"" + sensor + "\" has no axes; drop axis");
    ch.axis = ch.kind->has_axes ? axis[0] : '\0';
    if (ch.kind->name == "gyro" && ch.axis == 'x')
      c.fail_here(what + ": the gyro's axis x is the file's [truth]; a gyro channel is axis y or z");
    for (const ChannelConfig& other : channels)
      if (other.kind == ch.kind && other.axis == ch.axis)
        c.fail_here(what + ": " + ch.label() + " is simulated twice (line " + std::to_string(other.line) + ")");
    c.number("b0", ch.b0);
    c.number("white_noise", ch.white_noise, Rule::non_negative);
    if (const toml::table* t = c.table("terms")) {
      TableReader terms(*t, r.file(), what + ".terms");
      for (const effects::Effect* e : effects::registry()) {
        double coefficient = 0.0;
        terms.number(e->name, coefficient);
        if (coefficient != 0.0) ch.coefficient[std::string(e->name)] = coefficient;
      }
      terms.finish("the terms " + effects::names());
    }
    c.finish();
    channels.push_back(std::move(ch));
  }
  return channels;
}

GyroConfig load_gyro(const std::filesystem::path& file) {
  const toml::table root = parse(file);
  TableReader r(root, file.string(), "");
  GyroConfig gyro;
  // [truth]: b0 and the [truth] key of each of the paper's effects; [hidden]:
  // every other effect by its term name, and each effect's parameter by its
  // gyro key (sim/effects/effect.h).
  r.section("truth", [&](TableReader& c) {
    c.number("b0_dph", gyro.b0_dph);
    for (const effects::Effect* e : effects::registry())
      if (!e->hidden()) c.number(e->truth_key, gyro.coefficient[std::string(e->name)]);
  });
  if (const toml::table* t = r.table("hidden")) {
    TableReader c(*t, file.string(), "hidden");
    std::string parameter_keys;
    for (const effects::Effect* e : effects::registry())
      if (e->hidden()) {
        double coefficient = 0.0;
        c.number(e->name, coefficient);
        gyro.coefficient[std::string(e->name)] = coefficient;
      }
    for (const effects::Effect* e : effects::registry())
      if (e->parameter) {
        double value = e->parameter->simulator_default;
        c.number(e->parameter->gyro_key, value,
                 e->parameter->may_be_zero ? Rule::non_negative : Rule::positive);
        gyro.parameter[std::string(e->name)] = value;
        parameter_keys += (parameter_keys.empty() ? "" : ", ") + std::string(e->parameter->gyro_key);
      }
    c.finish("hidden terms " + effects::hidden_names() + ", and " + parameter_keys);
  }
  r.section("noise", [&](TableReader& c) {
    NoiseConfig& n = gyro.noise;
    c.number("arw_deg_per_sqrt_h", n.arw_deg_per_sqrt_h, Rule::non_negative);
    c.number("bias_instability_dph", n.bias_instability_dph, Rule::non_negative);
    c.number("flicker_tau_min_s", n.flicker_tau_min_s, Rule::positive);
    c.number("flicker_tau_max_s", n.flicker_tau_max_s, Rule::positive);
    c.integer("flicker_processes", n.flicker_processes, 1, 50);
    c.number("rrw_dph_per_sqrt_h", n.rrw_dph_per_sqrt_h, Rule::non_negative);
    c.number("quantization_arcsec", n.quantization_arcsec, Rule::non_negative);
    c.number("glitch_rate_per_h", n.glitch_rate_per_h, Rule::non_negative);
    c.number("glitch_size_dph", n.glitch_size_dph, Rule::non_negative);
    c.number("arw_temp_ref_c", n.arw_temp_ref_c);
    c.number("arw_temp_coeff_per_c2", n.arw_temp_coeff_per_c2, Rule::non_negative);
    if (n.flicker_tau_min_s > n.flicker_tau_max_s)
      c.fail_here("noise.flicker_tau_min_s must not exceed noise.flicker_tau_max_s");
  });
  gyro.channels = read_channels(r);
  r.finish();
  return gyro;
}

void check_scenario_against_rig(const Scenario& scenario, const RigConfig& rig,
                                const std::filesystem::path& rig_file) {
  if (!scenario.chamber) return;
  const ChamberConfig& ch = rig.chamber;
  const std::string range = "the chamber's range, " + TableReader::format(ch.min_c) + ".." +
                            TableReader::format(ch.max_c) + " °C (chamber.min_c/max_c in " +
                            rig_file.string() + ")";
  const auto outside = [&](double t) { return t < ch.min_c || t > ch.max_c; };
  if (outside(scenario.start_c))
    throw InputError(scenario.file.string() + ": start_c = " +
                     TableReader::format(scenario.start_c) + " °C is outside " + range);
  std::size_t index = 0;
  for (const Segment& s : scenario.segments) {
    ++index;
    if (s.kind != SegmentKind::free && outside(s.temp_c))
      throw InputError(located(scenario.file.string(), s.source_line,
                               "segment " + std::to_string(index) + ": " +
                                   (s.kind == SegmentKind::hold ? "temp_c" : "target_c") + " = " +
                                   TableReader::format(s.temp_c) + " °C is outside " + range));
  }
  // A lower bound on the power each segment needs: the chamber's own capacity
  // at the ramp rate plus what its walls exchange with the room (the load only
  // adds to it). Beyond the heater or cooler the chamber cannot follow.
  const Profile profile(scenario.start_c, scenario.segments);
  for (std::size_t i = 0; i < profile.segments().size(); ++i) {
    const Segment& s = profile.segments()[i];
    if (s.kind == SegmentKind::free) continue;
    const double from = s.kind == SegmentKind::ramp ? profile.segment_start_c(i) : s.temp_c;
    const double rate_c_per_s = s.kind == SegmentKind::ramp ? s.rate_c_per_min / 60.0 : 0.0;
    const bool heating = s.kind == SegmentKind::ramp ? s.temp_c > from : s.temp_c > scenario.room_c;
    const double hottest = std::max(from, s.temp_c), coldest = std::min(from, s.temp_c);
    const double wall_w = heating ? ch.insulation_w_per_k * (hottest - scenario.room_c)
                                  : ch.insulation_w_per_k * (scenario.room_c - coldest);
    const double need_w = ch.capacity_j_per_k * rate_c_per_s + std::max(0.0, wall_w);
    const double have_w = heating ? ch.heater_max_w : ch.cooler_max_w;
    if (need_w <= have_w) continue;
    const std::string what = s.kind == SegmentKind::ramp
                                 ? fmt::format("a {:g} °C/min ramp {} to {:g} °C", s.rate_c_per_min,
                                               heating ? "up" : "down", s.temp_c)
                                 : fmt::format("holding {:g} °C", s.temp_c);
    std::string advice;
    const double spare_w = have_w - std::max(0.0, wall_w);
    if (s.kind == SegmentKind::ramp && spare_w > 0.0)
      advice = fmt::format("; slow it to at most {:.1f} °C/min", spare_w / ch.capacity_j_per_k * 60.0);
    else
      advice = "; the chamber cannot hold that temperature against its wall losses";
    throw InputError(located(
        scenario.file.string(), s.source_line,
        fmt::format("segment {}: {} needs at least {:.1f} kW of {} (chamber capacity {:g} J/K at "
                    "{:.3g} °C/s, plus {:.2f} kW through the walls), but chamber.{} is {:g} W in "
                    "{}: the chamber cannot follow the profile{}",
                    i + 1, what, need_w / 1000.0, heating ? "heating" : "cooling",
                    ch.capacity_j_per_k, rate_c_per_s, std::max(0.0, wall_w) / 1000.0,
                    heating ? "heater_max_w" : "cooler_max_w", have_w, rig_file.string(), advice)));
  }
}

void apply_hidden_option(GyroConfig& gyro, std::string_view spec) {
  const std::size_t eq = spec.find('=');
  const std::string usage = "--hidden " + std::string(spec) +
                            ": expected TERM=COEF with TERM one of " + effects::hidden_names();
  if (eq == std::string_view::npos || eq == 0) throw InputError(usage);
  const std::string term(spec.substr(0, eq));
  const std::string value(spec.substr(eq + 1));
  const effects::Effect* effect = effects::find(term);
  if (effect == nullptr || !effect->hidden()) {
    std::string message =
        "--hidden: unknown term '" + term + "' (valid: " + effects::hidden_names() + ")";
    if (effect != nullptr)
      message += "; '" + term + "' is part of the true model, set it in the gyro file's [truth] (" +
                 std::string(effect->truth_key) + ")";
    else if (term == "1")
      message += "; '1' is part of the true model, set it in the gyro file's [truth] (b0_dph)";
    throw InputError(message);
  }
  double coefficient = 0.0;
  const auto result = std::from_chars(value.data(), value.data() + value.size(), coefficient);
  if (result.ec != std::errc() || result.ptr != value.data() + value.size() ||
      !std::isfinite(coefficient))
    throw InputError("--hidden " + std::string(spec) + ": '" + value +
                     "' is not a finite number");
  gyro.coefficient[term] = coefficient;
}

}  // namespace gyrotherm::sim
