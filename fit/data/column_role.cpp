#include "fit/data/column_role.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <set>

#include "fit/data/header_units.h"

namespace gyrotherm::fit {
namespace {

bool lower(char c) { return std::islower(static_cast<unsigned char>(c)) != 0; }
bool upper(char c) { return std::isupper(static_cast<unsigned char>(c)) != 0; }
bool digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool alnum(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; }

bool one_of(const std::string& word, std::initializer_list<std::string_view> list) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

bool starts_with_any(const std::string& word, std::initializer_list<std::string_view> stems) {
  return std::any_of(stems.begin(), stems.end(), [&](std::string_view s) { return word.starts_with(s); });
}

// g, a, m or w, an optional digit, then the axis (and an optional digit):
// "gx", "ay", "m1z", "wz2".
bool axis_word(const std::string& w) {
  if (w.empty() || std::string_view("gamw").find(w[0]) == std::string_view::npos) return false;
  std::size_t k = 1;
  if (k < w.size() && digit(w[k])) ++k;
  if (k >= w.size() || std::string_view("xyz").find(w[k]) == std::string_view::npos) return false;
  ++k;
  if (k < w.size() && digit(w[k])) ++k;
  return k == w.size();
}

// Units of acceleration and magnetic field as loggers write them in names.
bool motion_unit_word(const std::string& w) {
  return one_of(w, {"mps2", "ms2", "mg", "gauss", "mgauss", "ut", "nt", "tesla", "lsb_g"});
}

}  // namespace

const char* to_string(ColumnRole role) {
  switch (role) {
    case ColumnRole::cause: return "a possible cause";
    case ColumnRole::motion_sensor: return "another motion sensor's channel";
    case ColumnRole::status: return "a status word";
    case ColumnRole::counter: return "a counter";
    case ColumnRole::constant: return "constant";
    case ColumnRole::derived: return "a model's, truth's or compensation's column";
  }
  return "";
}

std::vector<std::string> column_words(std::string_view name) {
  std::vector<std::string> words;
  std::string word;
  const auto flush = [&] {
    if (!word.empty()) words.push_back(word);
    word.clear();
  };
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    if (!alnum(c)) {
      flush();
      continue;
    }
    if (!word.empty()) {
      const char p = name[i - 1];
      // A case change lower → upper ("AccX"), or letters ↔ digits ("mps2", "m1z").
      if ((lower(p) && upper(c)) || digit(p) != digit(c)) flush();
    }
    word += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  flush();
  return words;
}

std::string folded_name(std::string_view name) {
  std::string out;
  for (const char c : name)
    if (alnum(c)) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

ColumnRole role_by_name(std::string_view name) {
  const std::vector<std::string> words = column_words(name);
  for (const std::string& w : words)
    if (one_of(w, {"true", "truth", "model", "compensated", "residual"})) return ColumnRole::derived;
  if (unit_in_header(Quantity::gyro, name).unit != nullptr) return ColumnRole::motion_sensor;
  for (const std::string& w : words) {
    if (starts_with_any(w, {"gyr", "acc", "mag", "omega"}) || one_of(w, {"xgyro", "ygyro", "zgyro", "xacc", "yacc", "zacc",
                                                                         "xmag", "ymag", "zmag"}) ||
        axis_word(w) || motion_unit_word(w))
      return ColumnRole::motion_sensor;
  }
  // Words cut at digits, joined again: "mps2" (mps 2), "m/s^2" (m s 2), "m1z" (m 1 z).
  for (std::size_t i = 0; i + 1 < words.size(); ++i) {
    const std::string two = words[i] + words[i + 1];
    const std::string three = i + 2 < words.size() ? two + words[i + 2] : "";
    if (motion_unit_word(two) || axis_word(two) || (!three.empty() && (motion_unit_word(three) || axis_word(three))))
      return ColumnRole::motion_sensor;
  }
  for (const std::string& w : words) {
    if (one_of(w, {"status", "flags", "flag", "state", "mode", "valid", "error", "errors", "err", "health", "crc",
                   "checksum", "fault", "faults"}))
      return ColumnRole::status;
    if (one_of(w, {"count", "counter", "seq", "sequence", "index", "idx", "id", "frame", "sample", "packet"}))
      return ColumnRole::counter;
  }
  return ColumnRole::cause;
}

ColumnRole column_role(std::string_view name, std::span<const double> values) {
  const ColumnRole by_name = role_by_name(name);
  if (by_name != ColumnRole::cause || values.empty()) return by_name;
  std::set<double> distinct;
  bool integers = true;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    integers = integers && v == std::round(v);
    if (distinct.size() <= 3) distinct.insert(v);
  }
  if (distinct.size() <= 1) return ColumnRole::constant;
  if (integers && distinct.size() <= 3) return ColumnRole::status;
  // A counter: integers stepping up by the same amount every sample.
  if (integers && values.size() > 2) {
    const double step = values[1] - values[0];
    bool steady = step > 0.0;
    for (std::size_t i = 2; steady && i < values.size(); ++i) steady = values[i] - values[i - 1] == step;
    if (steady) return ColumnRole::counter;
  }
  return ColumnRole::cause;
}

}  // namespace gyrotherm::fit
