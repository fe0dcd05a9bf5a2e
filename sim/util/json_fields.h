#pragma once
// Reading a JSON input's fields by path, for the from_json of each struct a
// file holds (the fit file, plan's --noise): a field that is missing or not a
// finite number is an InputError naming it by its path from the object read
// ("coefficients.T^2: missing (the coefficient)", "components.arw.value: must
// be a finite number (°/√h)"); read_object reads a member by its from_json
// and puts the member's name before the path of an error inside it. Include
// only where nlohmann/json.hpp is already wanted (a .cpp file).

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "sim/util/input_error.h"

namespace gyrotherm::json_fields {

// obj[key], or InputError "PATH: missing (WHAT)".
inline const nlohmann::json& field_at(const nlohmann::json& obj, const std::string& key, const std::string& path,
                                      std::string_view what) {
  if (!obj.is_object() || !obj.contains(key)) throw InputError(fmt::format("{}: missing ({})", path, what));
  return obj[key];
}
// v as a finite number, or InputError "PATH: must be a finite number (WHAT)".
inline double finite_number(const nlohmann::json& v, const std::string& path, std::string_view what) {
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw InputError(fmt::format("{}: must be a finite number ({})", path, what));
  return v.get<double>();
}
inline double finite_at(const nlohmann::json& obj, const std::string& key, const std::string& path,
                        std::string_view what) {
  return finite_number(field_at(obj, key, path, what), path, what);
}
// The same at the top of the object read: the path is the key.
inline const nlohmann::json& field(const nlohmann::json& obj, const char* key, std::string_view what) {
  return field_at(obj, key, key, what);
}
inline double finite(const nlohmann::json& obj, const char* key, std::string_view what) {
  return finite_at(obj, key, key, what);
}
// An error from inside a member `key`, its path put after the member's name:
// "rate_hz: …" becomes "csv.rate_hz: …" (a path: a lower-case name followed
// by '.', '[', ':' or " ="); any other message ("expected an object …")
// follows "csv: ".
inline InputError inside(std::string_view key, const InputError& e) {
  const std::string_view inner = e.what();
  std::size_t k = 0;
  while (k < inner.size() && (std::isalnum(static_cast<unsigned char>(inner[k])) || inner[k] == '_')) ++k;
  const bool named = !inner.empty() && (std::islower(static_cast<unsigned char>(inner[0])) || inner[0] == '_');
  const std::string_view after = inner.substr(k);
  const bool path = named && (after.starts_with('.') || after.starts_with('[') || after.starts_with(':') ||
                              after.starts_with(" ="));
  return InputError(fmt::format("{}{}{}", key, path ? "." : ": ", inner));
}
// obj[key] read by its from_json, an error of a field inside it named by its
// path ("columns.csv.rate_hz").
template <class T>
void read_object(const nlohmann::json& obj, const char* key, std::string_view what, T& out) {
  const nlohmann::json& v = field(obj, key, what);
  try {
    from_json(v, out);
  } catch (const InputError& e) {
    throw inside(key, e);
  }
}

}  // namespace gyrotherm::json_fields
