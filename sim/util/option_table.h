#pragma once
// Options, declared once (docs/architecture.md, "Where the options live"):
// a command's (`gyrotherm fit --avg 100`) and an engine's (`--option
// fish=30`) are the same table. A command's table lists per option the names the command
// line takes ("--avg", "-o,--output", or a positional "data"), the keyword a
// Python caller writes ("avg", "output", "data"), the help the command line
// shows (it states the default and the unit), the option's kind, whether it
// is required, and the function that parses one value into the command's
// options struct. The command line (app/option_binding.h, with CLI11) and the
// Python package read the same tables; neither declares an option itself,
// and the struct's own initialisers are the defaults.
//
// A value is always text, as a command line gives it: "100" for a number,
// "true" or "false" for a flag, one element for a list (a list row's set
// appends). A value that does not parse is refused with an InputError
// naming the option, the value and what was expected ("--avg 'abc':
// expected a number"); the checks that need several options are in each
// command's request function (e.g. studies/options/fit_options.h).
//
// A row may carry a rule (OptionRule: a range, a whole number, a list of
// words): its setter refuses a value that breaks it ("--longest '800': must
// be > 0 and <= 720 h"), check_rules holds an options struct built in code to
// the same rules, and the help shows it. An engine's table names its rows by
// the KEY of --option KEY=VALUE (fit/engines/engine_options.h reads them with
// the engine's own messages).

#include <charconv>
#include <concepts>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace gyrotherm {

// What a value must be.
struct OptionRule {
  enum class Kind { integer, real, choice };
  Kind kind = Kind::real;
  double lower = 0.0;       // integer and real: lower ≤ value ≤ upper (an infinite upper: no bound)
  double upper = 0.0;
  bool lower_open = false;  // real: lower < value
  bool upper_open = false;  // real: value < upper
  // integer: one more value outside [lower, upper] that is allowed, how a
  // user writes it ("auto": only as that word; empty: as the number) and
  // what it means ("automatic").
  std::optional<double> extra;
  std::string_view extra_word;
  std::string_view extra_meaning;
  std::vector<std::string_view> choices;  // choice: the allowed words
  std::string_view unit;                  // "h", "s", "°C/min": after the bounds

  bool allows(double value) const;
  bool allows_word(std::string_view word) const;  // choice
  // "a whole number from 2 to 100000 (or auto)", "> 0 and <= 1", "> 0 s", "one of nw, ewc".
  std::string text() const;
};

// Rules, for the tables; kNoBound as an upper bound: none.
inline constexpr double kNoBound = std::numeric_limits<double>::infinity();
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
inline OptionRule number_in(double lower, double upper, std::string_view unit = {}) {
  return {.kind = OptionRule::Kind::real, .lower = lower, .upper = upper, .unit = unit};
}
inline OptionRule number_above(double lower, double upper, std::string_view unit = {}) {
  return {.kind = OptionRule::Kind::real, .lower = lower, .upper = upper, .lower_open = true, .unit = unit};
}
inline OptionRule one_of(std::vector<std::string_view> choices) {
  return {.kind = OptionRule::Kind::choice, .choices = std::move(choices)};
}
// A default as a user would write it: 0.25, 20000, auto, nw.
std::string option_value_text(double value, const OptionRule& rule);

// list: repeatable, one value each time (on the command line one value per
// name: `--add a --add b`, so that a positional after it is never taken for
// one).
enum class OptionKind { text, number, integer, flag, list };
// "text", "number", "integer", "flag", "list".
std::string_view kind_name(OptionKind kind);

template <class Options>
struct OptionRow {
  std::string names;    // as CLI11 takes them: "--avg", "-o,--output", or a positional "data"
  std::string keyword;  // the Python keyword: "avg", "output", "data", "time_col"
  // What the option is, without its default: the default is the struct's own
  // value, shown after the help as "(default: VALUE)" (shown_help), or the
  // default_note where it is not a value ("the fit's", "a quarter of the
  // record"). No help states a default itself (tests/option_table_test.cpp).
  std::string help;
  OptionKind kind = OptionKind::text;
  bool required = false;
  // Parses one value ("true"/"false" for a flag) into the options; throws
  // InputError naming the option and what was expected.
  std::function<void(Options&, const std::string& value)> set;
  // What --help shows after the names: "FLOAT", "INT", "UINT", "TEXT", for a
  // list "TEXT" (plan's --range: "FLOAT x 2"); "" for a flag.
  std::string value_name;
  // The field's value as a user would write it (a list's values joined by
  // ","; nothing for an optional not set); empty where the row has no field.
  std::function<std::optional<std::string>(const Options&)> get;
  // A list that takes several values after one name (plan's --range -20 50);
  // every other list one per name.
  bool several_per_name = false;
  std::string default_note;
  // What the value must be, where the option has a rule (with_rule).
  std::optional<OptionRule> rule;
  // A number or whole-number row: its field as a number (nothing for an
  // optional not set), and setting it from one.
  std::function<std::optional<double>(const Options&)> number;
  std::function<void(Options&, double)> set_number;
};



template <class Options>
struct OptionTable {
  std::string command;  // "fit", for messages
  std::vector<OptionRow<Options>> rows;
};

namespace detail {
// 'T + T^2 + dT' for a value with a blank, as a user would type it; else the value.
std::string quoted_if_spaced(const std::string& value);
}  // namespace detail

// A row without its setter: the command-line binding and docstrings.
struct OptionInfo {
  std::string names, keyword, help;
  OptionKind kind = OptionKind::text;
  bool required = false;
  std::string value_name;
  bool several_per_name = false;
  // The default as shown: the row's default_note, else the value a
  // default-constructed Options holds (a text, number or whole number that is
  // not empty; a flag is off and a list empty by default); "" for none.
  std::string default_value;
  std::optional<OptionRule> rule;
};
// The help with its default and rule: "Averaging window in seconds (default:
// 100)", "Longest test considered, h (default: 48; must be > 0 and <= 720 h)".
std::string shown_help(const OptionInfo& row);
// The value `defaults` hold for a text, number or whole-number row that is
// not required, as a user would write it; "" for any other row and an unset
// or empty value.
template <class Options>
std::string value_default(const OptionRow<Options>& r, const Options& defaults) {
  const bool valued = r.kind == OptionKind::text || r.kind == OptionKind::number || r.kind == OptionKind::integer;
  if (!valued || !r.get || r.required) return {};
  if (r.rule && r.number)
    if (const std::optional<double> x = r.number(defaults)) return option_value_text(*x, *r.rule);
  return detail::quoted_if_spaced(r.get(defaults).value_or(""));
}
template <class Options>
std::vector<OptionInfo> list_options(const OptionTable<Options>& table) {
  const Options defaults{};
  std::vector<OptionInfo> out;
  for (const OptionRow<Options>& r : table.rows) {
    OptionInfo info{r.names, r.keyword,          r.help,         r.kind,
                    r.required, r.value_name, r.several_per_name, r.default_note, r.rule};
    if (info.default_value.empty()) info.default_value = value_default(r, defaults);
    out.push_back(std::move(info));
  }
  return out;
}

// "avg" from "--avg", "output" from "-o,--output", "time_col" from "--time-col".
std::string keyword_of(std::string_view names);
// The name a message uses: the longest of the names ("--output").
std::string display_name(std::string_view names);

// An option whose value differs from the default, as a next step repeats it.
struct GivenOption {
  std::string flag;     // "--time-col"
  std::string keyword;  // "time_col"
  std::string value;    // "time_us"; "true" for a flag
  OptionKind kind = OptionKind::text;
};

// The rows whose field differs from a default-constructed Options', in order.
template <class Options>
std::vector<GivenOption> given_options(const std::vector<OptionRow<Options>>& rows, const Options& now) {
  const Options defaults{};
  std::vector<GivenOption> out;
  for (const OptionRow<Options>& r : rows) {
    if (!r.get) continue;
    const std::optional<std::string> value = r.get(now);
    if (value && value != r.get(defaults)) out.push_back({display_name(r.names), r.keyword, *value, r.kind});
  }
  return out;
}

using KeywordValues = std::vector<std::pair<std::string, std::string>>;

// For each (keyword, value), the row it sets, in order; throws InputError for
// an unknown keyword ("unknown option 'avgg' for fit; the options are: data,
// model, …"), a keyword that is not a list given twice, or a required row
// that is not given.
std::vector<std::size_t> rows_for_keywords(const std::string& command, const std::vector<OptionInfo>& rows,
                                           const KeywordValues& given);

// Sets `options` from keyword-value pairs (a Python call's keywords, a list
// given once per element), with every check of the command line.
template <class Options>
void apply_options(const OptionTable<Options>& table, Options& options, const KeywordValues& given) {
  const std::vector<std::size_t> rows = rows_for_keywords(table.command, list_options(table), given);
  for (std::size_t k = 0; k < given.size(); ++k) table.rows[rows[k]].set(options, given[k].second);
}

// The parsers of one value; `option` is the name for the message.
double parse_number(std::string_view option, const std::string& text);
bool parse_flag(std::string_view option, const std::string& text);
// "--seed '-1': expected a whole number >= 0", "--verify '1e99': out of range (a whole number from … to …)".
[[noreturn]] void reject_whole_number(std::string_view option, const std::string& text, bool is_unsigned,
                                      bool out_of_range, const std::string& lowest, const std::string& highest);
template <std::integral Int>
Int parse_whole(std::string_view option, const std::string& text) {
  const std::string_view digits = text.starts_with('+') ? std::string_view(text).substr(1) : std::string_view(text);
  Int value{};
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc() || end != digits.data() + digits.size() || digits.empty())
    reject_whole_number(option, text, std::is_unsigned_v<Int>, error == std::errc::result_out_of_range,
                        std::to_string(std::numeric_limits<Int>::lowest()), std::to_string(std::numeric_limits<Int>::max()));
  return value;
}

namespace detail {
template <class T> struct unwrap_optional { using type = T; };
template <class T> struct unwrap_optional<std::optional<T>> { using type = T; };
std::string number_text(double value);
template <class T>
std::optional<std::string> value_text(const T& v) {
  if constexpr (std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_same_v<T, bool>) {
    return std::string(v ? "true" : "false");
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    std::string joined;
    for (const std::string& e : v) joined += (joined.empty() ? "" : ",") + e;
    return joined;
  } else if constexpr (requires { v.has_value(); }) {
    if (!v) return std::nullopt;
    return value_text(*v);
  } else if constexpr (std::is_floating_point_v<T>) {
    return number_text(static_cast<double>(v));
  } else {
    return std::to_string(v);
  }
}
}  // namespace detail

// A row that parses its value into one field, the kind following the field's
// type: std::string (text), a floating point (number), an integer (integer;
// an unsigned one refuses a sign), bool (flag), std::optional of one of these
// (set when given), std::vector<std::string> (list: each value appended).
// `field` is a member pointer or a callable returning the field.
template <class Options, class Field>
OptionRow<Options> field_row(std::string names, std::string help, Field field, bool required = false) {
  using Ref = std::invoke_result_t<Field, Options&>;
  using T = std::remove_cvref_t<Ref>;
  using Value = typename detail::unwrap_optional<T>::type;
  OptionRow<Options> row{.names = names, .keyword = keyword_of(names), .help = std::move(help), .required = required};
  const std::string name = display_name(names);
  row.get = [field](const Options& o) -> std::optional<std::string> {
    const T& v = std::invoke(field, const_cast<Options&>(o));  // read only
    return detail::value_text(v);
  };
  if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    row.kind = OptionKind::list;
    row.value_name = "TEXT";
    row.set = [field](Options& o, const std::string& v) { std::invoke(field, o).push_back(v); };
  } else if constexpr (std::is_same_v<Value, std::string>) {
    row.kind = OptionKind::text;
    row.value_name = "TEXT";
    row.set = [field](Options& o, const std::string& v) { std::invoke(field, o) = v; };
  } else if constexpr (std::is_same_v<Value, bool>) {
    row.kind = OptionKind::flag;
    row.set = [field, name](Options& o, const std::string& v) { std::invoke(field, o) = parse_flag(name, v); };
  } else if constexpr (std::is_floating_point_v<Value>) {
    row.kind = OptionKind::number;
    row.value_name = "FLOAT";
    row.set = [field, name](Options& o, const std::string& v) {
      std::invoke(field, o) = static_cast<Value>(parse_number(name, v));
    };
  } else {
    static_assert(std::is_integral_v<Value>, "an option is text, a number, a flag or a list of text");
    row.kind = OptionKind::integer;
    row.value_name = std::is_unsigned_v<Value> ? "UINT" : "INT";
    row.set = [field, name](Options& o, const std::string& v) { std::invoke(field, o) = parse_whole<Value>(name, v); };
  }
  if constexpr (std::is_arithmetic_v<Value> && !std::is_same_v<Value, bool>) {
    row.number = [field](const Options& o) -> std::optional<double> {
      const T& v = std::invoke(field, const_cast<Options&>(o));  // read only
      if constexpr (std::is_same_v<T, Value>) {
        return static_cast<double>(v);
      } else {
        if (!v) return std::nullopt;
        return static_cast<double>(*v);
      }
    };
    row.set_number = [field](Options& o, double v) { std::invoke(field, o) = static_cast<Value>(v); };
  }
  return row;
}

// "--longest '800': must be > 0 and <= 720 h" (engines word it their own way).
[[noreturn]] void reject_rule(std::string_view option, const std::string& text, const OptionRule& rule);

// The row with a rule: its setter refuses a value that breaks it (a choice
// before it is set, a number once parsed).
template <class Options>
OptionRow<Options> with_rule(OptionRow<Options> row, OptionRule rule) {
  row.rule = rule;
  row.set = [set = std::move(row.set), number = row.number, rule, name = display_name(row.names)](
                Options& o, const std::string& v) {
    if (rule.kind == OptionRule::Kind::choice && !rule.allows_word(v)) reject_rule(name, v, rule);
    set(o, v);
    if (number)
      if (const std::optional<double> x = number(o); x && !rule.allows(*x)) reject_rule(name, v, rule);
  };
  return row;
}

// A row of one field with its rule, as engines declare theirs:
// ruled_row<O>("fish", "N, the swarm size", &O::fish, whole(2, 100000)).
template <class Options, class Field>
OptionRow<Options> ruled_row(std::string names, std::string help, Field field, OptionRule rule) {
  return with_rule(field_row<Options>(std::move(names), std::move(help), field), std::move(rule));
}

// The first row whose value breaks its rule in `options` (built in code):
// its index, and the value as a user would write it.
template <class Options>
std::optional<std::pair<std::size_t, std::string>> broken_rule(const OptionTable<Options>& table,
                                                               const Options& options) {
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    const OptionRow<Options>& r = table.rows[k];
    if (!r.rule) continue;
    if (r.number) {
      if (const std::optional<double> x = r.number(options); x && !r.rule->allows(*x))
        return std::pair{k, option_value_text(*x, *r.rule)};
    } else if (r.rule->kind == OptionRule::Kind::choice && r.get) {
      const std::string word = r.get(options).value_or("");
      if (!r.rule->allows_word(word)) return std::pair{k, word};
    }
  }
  return std::nullopt;
}

// Refuses, as the command line would, the first value in `options` (built in
// code, e.g. by a Python caller) that breaks its row's rule.
template <class Options>
void check_rules(const OptionTable<Options>& table, const Options& options) {
  if (const auto broken = broken_rule(table, options))
    reject_rule(display_name(table.rows[broken->first].names), broken->second, *table.rows[broken->first].rule);
}

// The row with its default in words, where it is not a value the struct holds.
template <class Options>
OptionRow<Options> defaulting(OptionRow<Options> row, std::string note) {
  row.default_note = std::move(note);
  return row;
}

// A row for a field of a member: (options.*outer).*inner, e.g. &O::request,
// &ExportRequest::format.
template <class Options, class Outer, class Inner, class T>
OptionRow<Options> nested_row(std::string names, std::string help, Outer Options::*outer, T Inner::*inner,
                              bool required = false) {
  return field_row<Options>(std::move(names), std::move(help),
                            [outer, inner](Options& o) -> T& { return (o.*outer).*inner; }, required);
}

// The rows of a part (e.g. the data options) as rows of a whole that holds it,
// `part` returning it: appended to `rows`.
template <class Whole, class Part, class Get>
void append_rows(std::vector<OptionRow<Whole>>& rows, const std::vector<OptionRow<Part>>& part_rows, Get part) {
  for (const OptionRow<Part>& r : part_rows) {
    OptionRow<Whole> w{r.names,          r.keyword,      r.help, r.kind, r.required, {}, r.value_name, {},
                       r.several_per_name, r.default_note, r.rule};
    w.set = [set = r.set, part](Whole& o, const std::string& v) { set(std::invoke(part, o), v); };
    if (r.get)
      w.get = [get = r.get, part](const Whole& o) { return get(std::invoke(part, const_cast<Whole&>(o))); };
    if (r.number) {
      w.number = [number = r.number, part](const Whole& o) { return number(std::invoke(part, const_cast<Whole&>(o))); };
      w.set_number = [set = r.set_number, part](Whole& o, double v) { set(std::invoke(part, o), v); };
    }
    rows.push_back(std::move(w));
  }
}

}  // namespace gyrotherm
