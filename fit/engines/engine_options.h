#pragma once
// Engine options, declared once (docs/architecture.md, "House rules").
//
// Each engine lists its own options in one table: the key a user writes
// (`--option KEY=VALUE`), the field of its Options aggregate, the rule the
// value must keep, and a line of help; the default is the aggregate's own.
// The table drives all three places an option appears:
//
//   read_options()      parses KEY=VALUE strings into Options (unknown keys,
//                       non-numbers and values that break the rule are
//                       refused, naming the engine, KEY=VALUE and the rule);
//   check_options()     Options::validate(): the same rules on an aggregate
//                       built in code (designated initialisers);
//   describe_options()  the `gyrotherm engines` listing and the contract
//                       tests (tests/engine_contract_test.cpp).
//
// A rule the table cannot say (one option bounding another) stays in the
// engine's validate(), after check_options().

#include <fmt/format.h>

#include <functional>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

// What a value must be.
struct OptionRule {
  enum class Kind { integer, real, choice };
  Kind kind = Kind::real;
  double lower = 0.0;       // integer and real: lower ≤ value ≤ upper
  double upper = 0.0;
  bool lower_open = false;  // real: lower < value
  // integer: one more value outside [lower, upper] that is allowed, how a
  // user writes it ("auto": only as that word; empty: as the number) and
  // what it means ("automatic").
  std::optional<double> extra;
  std::string_view extra_word;
  std::string_view extra_meaning;
  std::vector<std::string_view> choices;  // choice: the allowed words

  bool allows(double value) const;
  bool allows_word(std::string_view word) const;  // choice
  // "a whole number from 2 to 100000 (or auto)", "> 0 and <= 1", "one of nw, ewc".
  std::string text() const;
};

// An option as the listing and the tests see it, whatever its engine.
struct OptionInfo {
  std::string key;
  OptionRule rule;
  std::string default_value;  // as a user would write it
  std::string help;
  // The listing's line: "DEFAULT: help [rule]".
  std::string line() const;
};

// One row of an engine's table: the key, the field (an int, a double or a
// std::string of Options), its rule and help.
template <class Options>
struct EngineOption {
  template <class T>
  EngineOption(std::string_view key_, T Options::*field, OptionRule rule_, std::string_view help_)
      : key(key_), rule(std::move(rule_)), help(help_) {
    if constexpr (std::is_same_v<T, std::string>) {
      get_text = [field](const Options& o) { return o.*field; };
      set_text = [field](Options& o, const std::string& v) { o.*field = v; };
    } else {
      static_assert(std::is_arithmetic_v<T>, "an option is a number or a string");
      get_number = [field](const Options& o) { return static_cast<double>(o.*field); };
      set_number = [field](Options& o, double v) { o.*field = static_cast<T>(v); };
    }
  }
  bool is_text() const { return static_cast<bool>(get_text); }

  std::string_view key;
  OptionRule rule;
  std::string_view help;
  std::function<double(const Options&)> get_number;
  std::function<void(Options&, double)> set_number;
  std::function<std::string(const Options&)> get_text;
  std::function<void(Options&, const std::string&)> set_text;
};

template <class Options>
using OptionTable = std::vector<EngineOption<Options>>;

// Parses one value for `rule` (a number, or the rule's extra word); throws
// InputError "ENGINE option KEY=TEXT: expected a number" or "...: must be RULE".
double parse_option_number(std::string_view engine, std::string_view key, const std::string& text,
                           const OptionRule& rule);
[[noreturn]] void reject_option(std::string_view engine, std::string_view key,
                                const std::string& text, const OptionRule& rule);
// "ENGINE has no option 'KEY' (its options: a, b)".
[[noreturn]] void reject_unknown_option(std::string_view engine, std::string_view key,
                                        const std::vector<std::string>& known);
// A default as a user would write it: 0.25, 20000, auto, nw.
std::string option_value_text(double value, const OptionRule& rule);

template <class Options>
void read_options(std::string_view engine, const OptionTable<Options>& table,
                  const std::map<std::string, std::string>& given, Options& o) {
  for (const auto& [key, text] : given) {
    const EngineOption<Options>* row = nullptr;
    for (const auto& r : table)
      if (r.key == key) row = &r;
    if (row == nullptr) {
      std::vector<std::string> known;
      for (const auto& r : table) known.emplace_back(r.key);
      reject_unknown_option(engine, key, known);
    }
    if (!row->is_text()) {
      row->set_number(o, parse_option_number(engine, key, text, row->rule));
      continue;
    }
    if (!row->rule.allows_word(text)) reject_option(engine, key, text, row->rule);
    row->set_text(o, text);
  }
}

template <class Options>
void check_options(std::string_view engine, const OptionTable<Options>& table, const Options& o) {
  for (const auto& row : table) {
    if (row.is_text()) {
      if (!row.rule.allows_word(row.get_text(o))) reject_option(engine, row.key, row.get_text(o), row.rule);
    } else if (const double v = row.get_number(o); !row.rule.allows(v)) {
      reject_option(engine, row.key, fmt::format("{}", v), row.rule);
    }
  }
}

template <class Options>
std::vector<OptionInfo> describe_options(const OptionTable<Options>& table,
                                         const Options& defaults = {}) {
  std::vector<OptionInfo> out;
  for (const auto& row : table)
    out.push_back({std::string(row.key), row.rule,
                   row.is_text() ? row.get_text(defaults)
                                 : option_value_text(row.get_number(defaults), row.rule),
                   std::string(row.help)});
  return out;
}

// Rules, for the tables.
inline OptionRule whole(double lower, double upper) {
  return {.kind = OptionRule::Kind::integer, .lower = lower, .upper = upper};
}
inline OptionRule whole_or_auto(double lower, double upper) {
  return {.kind = OptionRule::Kind::integer, .lower = lower, .upper = upper, .extra = 0.0,
          .extra_word = "auto", .extra_meaning = "automatic"};
}
inline OptionRule whole_or_zero(double lower, double upper, std::string_view meaning) {
  return {.kind = OptionRule::Kind::integer, .lower = lower, .upper = upper, .extra = 0.0,
          .extra_meaning = meaning};
}
inline OptionRule number_in(double lower, double upper) {
  return {.kind = OptionRule::Kind::real, .lower = lower, .upper = upper};
}
inline OptionRule number_above(double lower, double upper) {
  return {.kind = OptionRule::Kind::real, .lower = lower, .upper = upper, .lower_open = true};
}
inline OptionRule one_of(std::vector<std::string_view> choices) {
  return {.kind = OptionRule::Kind::choice, .choices = std::move(choices)};
}

}  // namespace gyrotherm::fit
