#include "studies/options/option_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "sim/util/comma_list.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {

std::string shown_help(const OptionInfo& row) {
  return row.default_value.empty() ? row.help : fmt::format("{} (default: {})", row.help, row.default_value);
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

}  // namespace gyrotherm::studies
