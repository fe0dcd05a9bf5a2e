#include "fit/engines/engine_options.h"

#include <charconv>

namespace gyrotherm::fit {

bool OptionRule::allows(double value) const {
  if (kind == Kind::choice) return false;
  if (!std::isfinite(value)) return false;
  if (extra && value == *extra) return true;
  if (kind == Kind::integer && value != std::floor(value)) return false;
  if (lower_open ? value <= lower : value < lower) return false;
  return value <= upper;
}

bool OptionRule::allows_word(std::string_view word) const {
  for (std::string_view c : choices)
    if (c == word) return true;
  return false;
}

std::string OptionRule::text() const {
  switch (kind) {
    case Kind::integer: {
      const std::string range = fmt::format("a whole number from {} to {}", lower, upper);
      if (!extra) return range;
      if (!extra_word.empty()) return fmt::format("{} (or {})", range, extra_word);
      return fmt::format("{} ({}) or {}", *extra, extra_meaning, range);
    }
    case Kind::real:
      return fmt::format("{} {} and <= {}", lower_open ? ">" : ">=", lower, upper);
    case Kind::choice: {
      std::string list;
      for (std::string_view c : choices) list += (list.empty() ? "" : ", ") + std::string(c);
      return "one of " + list;
    }
  }
  return "";
}

std::string OptionInfo::line() const {
  return fmt::format("{}: {} [{}]", default_value, help, rule.text());
}

void reject_option(std::string_view engine, std::string_view key, const std::string& text,
                   const OptionRule& rule) {
  throw InputError(fmt::format("{} option {}={}: must be {}", engine, key, text, rule.text()));
}

void reject_unknown_option(std::string_view engine, std::string_view key,
                           const std::vector<std::string>& known) {
  std::string list;
  for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
  throw InputError(fmt::format("{} has no option '{}' (its options: {})", engine, key,
                               list.empty() ? "none" : list));
}

double parse_option_number(std::string_view engine, std::string_view key, const std::string& text,
                           const OptionRule& rule) {
  if (rule.extra && !rule.extra_word.empty() && text == rule.extra_word) return *rule.extra;
  double v = 0.0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !std::isfinite(v))
    throw InputError(fmt::format("{} option {}={}: expected a number", engine, key, text));
  // A value that has a word (auto) is written as the word, never as the
  // number that stands for it inside Options.
  const bool word_only = rule.extra && !rule.extra_word.empty() && v == *rule.extra;
  if (word_only || !rule.allows(v)) reject_option(engine, key, text, rule);
  return v;
}

std::string option_value_text(double value, const OptionRule& rule) {
  if (rule.extra && value == *rule.extra && !rule.extra_word.empty()) return std::string(rule.extra_word);
  return fmt::format("{}", value);
}

}  // namespace gyrotherm::fit
