#include "fit/data/header_units.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <vector>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

// Lower case, "°"/"º" → "deg", "µ"/"μ" → "u", "²" → "2", spaces dropped.
std::string normalised(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::string_view rest = text.substr(i);
    if (rest.starts_with("\xC2\xB0") || rest.starts_with("\xC2\xBA")) {
      out += "deg";
      ++i;
    } else if (rest.starts_with("\xC2\xB5") || rest.starts_with("\xCE\xBC")) {
      out += 'u';
      ++i;
    } else if (rest.starts_with("\xC2\xB2")) {  // "m/s²" → "m/s2"
      out += '2';
      ++i;
    } else if (!std::isspace(c)) {
      out += static_cast<char>(std::tolower(c));
    }
  }
  return out;
}

const Unit* by_alias(Quantity q, const std::string& token) {
  if (token.empty()) return nullptr;
  for (const Unit& u : unit_table()) {
    if (u.quantity != q) continue;
    std::string_view aliases = u.aliases;
    while (!aliases.empty()) {
      const std::size_t space = aliases.find(' ');
      if (aliases.substr(0, space) == token) return &u;
      if (space == std::string_view::npos) break;
      aliases.remove_prefix(space + 1);
    }
  }
  return nullptr;
}

bool is_raw_counts(const std::string& token) {
  static constexpr std::array<std::string_view, 8> kRaw = {"lsb", "lsbs", "count", "counts", "raw", "adc", "digits", "cnt"};
  return std::find(kRaw.begin(), kRaw.end(), token) != kRaw.end();
}

}  // namespace

HeaderUnit unit_in_header(Quantity quantity, std::string_view column) {
  HeaderUnit out;
  const std::string_view name = trim(column);
  if (name.empty()) return out;
  // In brackets at the end: a statement.
  if (name.back() == ')' || name.back() == ']') {
    const char open = name.back() == ')' ? '(' : '[';
    const std::size_t at = name.rfind(open);
    if (at != std::string_view::npos) {
      const std::string_view inside = trim(name.substr(at + 1, name.size() - at - 2));
      out.said = std::string(inside);
      const std::string token = normalised(inside);
      out.unit = by_alias(quantity, token);
      out.raw_counts = out.unit == nullptr && is_raw_counts(token);
      return out;
    }
  }
  // The last word, when there are several.
  if (const std::size_t space = name.find_last_of(" \t"); space != std::string_view::npos) {
    const std::string_view word = name.substr(space + 1);
    if (const Unit* u = by_alias(quantity, normalised(word))) {
      out.unit = u;
      out.said = std::string(word);
      return out;
    }
  }
  // The last one, two or three _-separated parts ("_s", "_rad_s" as rad/s or rad_s).
  std::vector<std::string_view> parts;
  for (std::string_view rest = name;;) {
    const std::size_t underscore = rest.find('_');
    parts.push_back(rest.substr(0, underscore));
    if (underscore == std::string_view::npos) break;
    rest.remove_prefix(underscore + 1);
  }
  for (std::size_t n = 1; n <= 3 && n < parts.size(); ++n) {
    std::string with_slash, with_underscore;
    for (std::size_t k = parts.size() - n; k < parts.size(); ++k) {
      if (!with_slash.empty()) {
        with_slash += '/';
        with_underscore += '_';
      }
      with_slash += parts[k];
      with_underscore += parts[k];
    }
    for (const std::string& token : {with_underscore, with_slash}) {
      if (const Unit* u = by_alias(quantity, normalised(token))) {
        out.unit = u;
        out.said = token;
        return out;
      }
    }
  }
  return out;
}

Units resolve_units(const Units& requested, const std::string& time_column, const std::string& temp_column,
                    const std::string& gyro_column, const std::string& temp2_column) {
  Units r = requested;
  struct Column {
    Quantity quantity;
    std::string* unit;
    std::string* from;
    const std::string& name;
    std::string_view option, what, scale_options;
    bool scaled;
    bool given;  // by an option (or a fit file), not by the header
    bool weak;   // from a fit file whose record's header or default gave it: this header wins
  };
  const bool temp_scaled = r.temp_scale != 1.0 || r.temp_offset != 0.0;
  std::vector<Column> columns = {
      {Quantity::time, &r.time, &r.time_from, time_column, "--time-unit", "time", "", false, !r.time.empty(), r.time_weak},
      {r.kind().quantity, &r.gyro, &r.gyro_from, gyro_column, "--gyro-unit", r.kind().noun, "--gyro-scale",
       r.gyro_scale != 1.0, !r.gyro.empty(), r.gyro_weak},
      {Quantity::temperature, &r.temp, &r.temp_from, temp_column, "--temp-unit", "temperature",
       "--temp-scale and --temp-offset", temp_scaled, !r.temp.empty(), r.temp_weak}};
  if (!temp2_column.empty())
    columns.push_back({Quantity::temperature, &r.temp, &r.temp_from, temp2_column, "--temp-unit",
                       "temperature", "--temp-scale and --temp-offset", temp_scaled, !r.temp.empty(), r.temp_weak});
  // The measured column's name stating another sensor kind's unit (gyro_dph
  // read as an accelerometer, accel_mps2 as a gyro), or naming another kind
  // and not its own (AccX, BARO.Press read as a gyro; GyrX as an
  // accelerometer): its numbers are that sensor's. A unit given as an option
  // (--gyro-unit) overrides: the user states what the column holds.
  const bool unit_typed = !r.gyro.empty() && !r.gyro_weak;
  if (!unit_typed && unit_in_header(r.kind().quantity, gyro_column).unit == nullptr)
    for (const SensorKind& other : sensor_kinds()) {
      if (&other == &r.kind()) continue;
      const HeaderUnit h = unit_in_header(other.quantity, gyro_column);
      const bool by_unit = h.unit != nullptr && h.said.size() > 1;  // (not a lone "g" or "t")
      const bool by_name = names_sensor(gyro_column, other) && !names_sensor(gyro_column, r.kind());
      if (by_unit || by_name)
        throw InputError(fmt::format(
            "column '{}' {}, but it is read as the {}'s (--sensor {}): give --sensor {}, or name the {}'s column "
            "with --gyro-col (or give --gyro-unit if the column is the {}'s after all)",
            gyro_column,
            by_unit ? fmt::format("states {} ({}), a unit of the {}", h.unit->name, h.unit->meaning, other.noun)
                    : fmt::format("is named as the {}'s", other.noun),
            r.kind().noun, r.kind().name, other.name, r.kind().noun, r.kind().noun));
    }
  std::vector<const std::string*> header_set;  // units a header set in this loop
  for (const Column& c : columns) {
    const HeaderUnit h = unit_in_header(c.quantity, c.name);
    if (h.raw_counts && !c.scaled)
      throw InputError(fmt::format(
          "column '{}' holds raw counts ({}): give {} to turn them into {}, with the unit they "
          "give",
          c.name, h.said, c.scale_options.empty() ? c.option : c.scale_options, c.what));
    if (h.unit != nullptr &&
        std::find(header_set.begin(), header_set.end(), c.unit) != header_set.end()) {
      // The other temperature column's header said it first (and is named as its source).
      if (*c.unit != h.unit->name)
        throw InputError(fmt::format(
            "the temperature columns state different units ({}: {}; '{}': {}); they are read "
            "with one --temp-unit",
            *c.from, *c.unit, c.name, h.unit->name));
      continue;
    }
    if (h.unit != nullptr && (!c.given || c.weak)) {  // the header names it; it wins over a fit's untyped unit
      *c.unit = std::string(h.unit->name);
      *c.from = fmt::format("header '{}'", c.name);
      header_set.push_back(c.unit);
      continue;
    }
    if (c.given) {
      const Unit& u = find_unit(c.quantity, *c.unit, c.option);
      if (c.from->empty()) *c.from = std::string(c.option);
      if (h.unit != nullptr && h.unit != &u) {
        // Numbers in another unit than the name says (kelvin under temp_c): an
        // offset or a scale reads them without renaming the column.
        std::string instead;
        if (c.quantity == Quantity::temperature && h.unit->name == "C" && u.name == "K")
          instead = "; if the numbers are kelvin under a name that says °C, give --temp-offset -273.15 instead";
        else if (c.quantity == Quantity::temperature && h.unit->name == "K" && u.name == "C")
          instead = "; if the numbers are °C under a name that says K, give --temp-offset 273.15 instead";
        throw InputError(fmt::format(
            "column '{}' states its unit as {} ({}), but {} gives {} ({}): the numbers cannot be "
            "in both; correct the one that is wrong{}",
            c.name, h.unit->name, h.unit->meaning, *c.from, u.name, u.meaning, instead));
      }
      continue;
    }
    if (h.unknown())
      throw InputError(fmt::format(
          "column '{}' states the unit '{}', which is no {} unit gyrotherm knows ({}): give {} "
          "with the unit of its numbers",
          c.name, h.said, c.what, unit_names(c.quantity, " or "), c.option));
  }
  for (const Column& c : columns) {
    if (!c.unit->empty()) continue;
    *c.unit = std::string(base_unit(c.quantity));
    *c.from = "default";
  }
  return r;
}

}  // namespace gyrotherm::fit
