#include "fit/engines/engine_options.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

std::string option_line(const OptionInfo& option) {
  return fmt::format("{}: {} [{}]", option.default_value, option.help, option.rule ? option.rule->text() : "");
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

}  // namespace gyrotherm::fit
