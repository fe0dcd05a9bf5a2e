#pragma once
// Engine options, declared once (docs/architecture.md, "House rules").
//
// Each engine lists its own options in one table, of the same type as a
// command's (sim/util/option_table.h): per row the key a user writes
// (`--option KEY=VALUE`), the field of its Options aggregate, the rule the
// value must keep, and a line of help; the default is the aggregate's own.
// The table drives all three places an option appears:
//
//   read_options()      parses KEY=VALUE strings into Options (unknown keys,
//                       non-numbers and values that break the rule are
//                       refused, naming the engine, KEY=VALUE and the rule);
//   check_options()     Options::validate(): the same rules on an aggregate
//                       built in code (designated initialisers);
//   list_options()      the `gyrotherm engines` listing and the contract
//                       tests (tests/engine_contract_test.cpp).
//
// A rule the table cannot say (one option bounding another) stays in the
// engine's validate(), after check_options().

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sim/util/option_table.h"

namespace gyrotherm::fit {

// Parses one value for `rule` (a number, or the rule's extra word); throws
// InputError "ENGINE option KEY=TEXT: expected a number" or "...: must be RULE".
double parse_option_number(std::string_view engine, std::string_view key, const std::string& text,
                           const OptionRule& rule);
[[noreturn]] void reject_option(std::string_view engine, std::string_view key,
                                const std::string& text, const OptionRule& rule);
// "ENGINE has no option 'KEY' (its options: a, b)".
[[noreturn]] void reject_unknown_option(std::string_view engine, std::string_view key,
                                        const std::vector<std::string>& known);
// The listing's line of an option: "DEFAULT: help [rule]".
std::string option_line(const OptionInfo& option);

// (The table's `command` is the engine's name.)
template <class Options>
void read_options(const OptionTable<Options>& table, const std::map<std::string, std::string>& given, Options& o) {
  const std::string& engine = table.command;
  for (const auto& [key, text] : given) {
    const OptionRow<Options>* row = nullptr;
    for (const auto& r : table.rows)
      if (r.keyword == key) row = &r;
    if (row == nullptr) {
      std::vector<std::string> known;
      for (const auto& r : table.rows) known.push_back(r.keyword);
      reject_unknown_option(engine, key, known);
    }
    if (row->set_number) {
      row->set_number(o, parse_option_number(engine, key, text, *row->rule));
      continue;
    }
    if (!row->rule->allows_word(text)) reject_option(engine, key, text, *row->rule);
    row->set(o, text);
  }
}

template <class Options>
void check_options(const OptionTable<Options>& table, const Options& o) {
  if (const auto broken = broken_rule(table, o))
    reject_option(table.command, table.rows[broken->first].keyword, broken->second, *table.rows[broken->first].rule);
}

}  // namespace gyrotherm::fit
