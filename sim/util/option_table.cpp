#include "sim/util/option_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "sim/util/comma_list.h"
#include "sim/util/input_error.h"

namespace gyrotherm {

bool OptionRule::allows(double value) const {
  if (kind == Kind::choice) return false;
  if (!std::isfinite(value)) return false;
  if (extra && value == *extra) return true;
  if (kind == Kind::integer && value != std::floor(value)) return false;
  if (lower_open ? value <= lower : value < lower) return false;
  return upper_open ? value < upper : value <= upper;
}

bool OptionRule::allows_word(std::string_view word) const {
  return std::find(choices.begin(), choices.end(), word) != choices.end();
}

std::string OptionRule::text() const {
  const std::string after = unit.empty() ? std::string() : fmt::format(" {}", unit);
  switch (kind) {
    case Kind::integer: {
      const std::string range = std::isinf(upper) ? fmt::format("a whole number >= {}{}", lower, after)
                                                  : fmt::format("a whole number from {} to {}{}", lower, upper, after);
      if (!extra) return range;
      if (!extra_word.empty()) return fmt::format("{} (or {})", range, extra_word);
      return fmt::format("{} ({}) or {}", *extra, extra_meaning, range);
    }
    case Kind::real: {
      const std::string low = fmt::format("{} {}", lower_open ? ">" : ">=", lower);
      if (std::isinf(upper)) return low + after;
      return fmt::format("{} and {} {}{}", low, upper_open ? "<" : "<=", upper, after);
    }
    case Kind::choice: return fmt::format("one of {}", fmt::join(choices, ", "));
  }
  return "";
}

std::string option_value_text(double value, const OptionRule& rule) {
  if (rule.extra && value == *rule.extra && !rule.extra_word.empty()) return std::string(rule.extra_word);
  return fmt::format("{}", value);
}

void reject_rule(std::string_view option, const std::string& text, const OptionRule& rule) {
  throw InputError(fmt::format("{} '{}': must be {}", option, text, rule.text()));
}

std::string shown_help(const OptionInfo& row) {
  std::string within;
  if (!row.default_value.empty()) within = "default: " + row.default_value;
  if (row.rule) within += (within.empty() ? "must be " : "; must be ") + row.rule->text();
  return within.empty() ? row.help : fmt::format("{} ({})", row.help, within);
}

std::string_view kind_name(OptionKind kind) {
  switch (kind) {
    case OptionKind::text: return "text";
    case OptionKind::number: return "number";
    case OptionKind::integer: return "integer";
    case OptionKind::flag: return "flag";
    case OptionKind::list: return "list";
  }
  return "text";
}

std::string display_name(std::string_view names) {
  std::string best;
  for (const std::string& n : split_commas(std::string(names)))
    if (n.size() > best.size()) best = n;
  return best;
}

std::string keyword_of(std::string_view names) {
  std::string k = display_name(names);
  k.erase(0, k.find_first_not_of('-'));
  std::replace(k.begin(), k.end(), '-', '_');
  return k;
}

std::vector<std::size_t> rows_for_keywords(const std::string& command, const std::vector<OptionInfo>& rows,
                                           const KeywordValues& given) {
  std::vector<std::size_t> out;
  std::set<std::size_t> seen;
  for (const auto& [keyword, value] : given) {
    const std::string& wanted = keyword;  // (clang before 16 cannot capture a structured binding)
    const auto row = std::find_if(rows.begin(), rows.end(), [&](const OptionInfo& r) { return r.keyword == wanted; });
    if (row == rows.end()) {
      std::vector<std::string> known;
      for (const OptionInfo& r : rows) known.push_back(r.keyword);
      throw InputError(fmt::format("unknown option '{}' for {}; the options are: {}", keyword, command,
                                   fmt::join(known, ", ")));
    }
    const auto index = static_cast<std::size_t>(row - rows.begin());
    if (!seen.insert(index).second && row->kind != OptionKind::list)
      throw InputError(fmt::format("{}: option '{}' is given twice (it takes one value)", command, keyword));
    out.push_back(index);
  }
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].required && !seen.contains(i))
      throw InputError(fmt::format("{}: option '{}' is required ({})", command, rows[i].keyword, rows[i].help));
  return out;
}

namespace detail {
std::string number_text(double value) { return fmt::format("{}", value); }
std::string quoted_if_spaced(const std::string& value) {
  return value.find(' ') == std::string::npos ? value : "'" + value + "'";
}
}  // namespace detail

double parse_number(std::string_view option, const std::string& text) {
  const std::string_view digits = text.starts_with('+') ? std::string_view(text).substr(1) : std::string_view(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc() || end != digits.data() + digits.size() || digits.empty())
    throw InputError(fmt::format("{} '{}': expected a number", option, text));
  return value;
}

bool parse_flag(std::string_view option, const std::string& text) {
  if (text == "true" || text == "1") return true;
  if (text == "false" || text == "0") return false;
  throw InputError(fmt::format("{} '{}': expected true or false", option, text));
}

void reject_whole_number(std::string_view option, const std::string& text, bool is_unsigned, bool out_of_range,
                         const std::string& lowest, const std::string& highest) {
  if (out_of_range)
    throw InputError(fmt::format("{} '{}': out of range (a whole number from {} to {})", option, text, lowest, highest));
  throw InputError(fmt::format("{} '{}': expected a whole number{}", option, text, is_unsigned ? " >= 0" : ""));
}

}  // namespace gyrotherm
