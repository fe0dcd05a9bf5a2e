// The commands' option tables (studies/options/): every row of every table
// sets the field the command line sets from a good value, refuses a bad
// number naming the option, and `gyrotherm CMD --help` lists exactly the
// table's names; apply_options (the Python side) lists the options on an
// unknown keyword and enforces the required ones.

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "fit/engines/engine.h"
#include "studies/options/allan_options.h"
#include "studies/options/check_options.h"
#include "studies/options/compensate_options.h"
#include "studies/options/diagnose_options.h"
#include "studies/options/export_options.h"
#include "studies/options/fit_options.h"
#include "studies/options/option_reference.h"
#include "studies/options/plan_options.h"
#include "studies/options/report_options.h"
#include "studies/options/reproduce_options.h"
#include "studies/options/score_options.h"
#include "studies/options/simulate_options.h"

namespace gyrotherm::studies {
namespace {

using gyrotherm::testing::CliResult;
using gyrotherm::testing::expect_input_error;
using gyrotherm::testing::run_cli;
using gyrotherm::testing::ScratchDir;

// A field as text, to compare with what was given.
std::string text(const std::string& s) { return s; }
std::string text(bool b) { return b ? "true" : "false"; }
template <class T>
  requires std::is_arithmetic_v<T>
std::string text(T v) {
  return fmt::format("{}", v);
}
template <class T>
std::string text(const std::optional<T>& v) {
  return v ? text(*v) : "(unset)";
}
template <class T>
std::string text(const std::vector<T>& v) {
  std::vector<std::string> items;
  for (const T& x : v) items.push_back(text(x));
  return fmt::format("{}", fmt::join(items, "|"));
}

// A row given `value` (once per element, "|"-separated) leaves the field
// `read` returns as `expected` (default: the value).
template <class O>
struct RowCase {
  std::string keyword, value;
  std::function<std::string(const O&)> read;
  std::string expected = "";
};
#define FIELD(expr) [](const auto& o) { return text(o.expr); }

// The cases of a part's rows (e.g. the data options) as cases of the whole.
template <class O, class Part, class Get>
std::vector<RowCase<O>> lift(std::vector<RowCase<O>> into, const std::vector<RowCase<Part>>& cases, Get part) {
  for (const RowCase<Part>& c : cases)
    into.push_back({c.keyword, c.value, [read = c.read, part](const O& o) { return read(std::invoke(part, o)); },
                    c.expected});
  return into;
}

template <class O>
const OptionRow<O>& row_of(const OptionTable<O>& table, const std::string& keyword) {
  for (const OptionRow<O>& r : table.rows)
    if (r.keyword == keyword) return r;
  ADD_FAILURE() << "no row " << keyword;
  return table.rows.front();
}

// Every row has a case, and each case sets its field from a default struct.
template <class O>
void expect_rows(const OptionTable<O>& table, const std::vector<RowCase<O>>& cases) {
  std::set<std::string> keywords, covered;
  for (const OptionRow<O>& r : table.rows) {
    SCOPED_TRACE(r.names);
    EXPECT_TRUE(keywords.insert(r.keyword).second) << "keyword twice";
    EXPECT_EQ(r.keyword, keyword_of(r.names));
    EXPECT_FALSE(r.help.empty());
    EXPECT_TRUE(r.set);
    EXPECT_EQ(r.value_name.empty(), r.kind == OptionKind::flag);
  }
  for (const RowCase<O>& c : cases) {
    SCOPED_TRACE(table.command + " " + c.keyword + " " + c.value);
    covered.insert(c.keyword);
    const OptionRow<O>& row = row_of(table, c.keyword);
    O o;
    std::stringstream values(c.value);
    for (std::string v; std::getline(values, v, '|');) row.set(o, v);
    EXPECT_EQ(c.read(o), c.expected.empty() ? c.value : c.expected);
    if (row.kind == OptionKind::number || row.kind == OptionKind::integer) {
      O bad;
      expect_input_error([&] { row.set(bad, "abc"); }, {display_name(row.names) + " 'abc': expected a"});
    }
    if (row.kind == OptionKind::integer)
      expect_input_error([&] { row.set(o, "1.5"); }, {display_name(row.names) + " '1.5': expected a whole number"});
  }
  EXPECT_EQ(covered, keywords) << table.command << ": a row without a case, or a case without a row";
}

std::vector<RowCase<fit::ColumnMap>> column_cases() {
  return {{"time_col", "t", FIELD(time)}, {"temp_col", "temp", FIELD(temp)}, {"gyro_col", "gx,gy", FIELD(gyro)},
          {"temp2_col", "far", FIELD(temp2)}, {"time_unit", "ms", FIELD(units.time)},
          {"gyro_unit", "dps", FIELD(units.gyro)}, {"sensor", "accel", FIELD(units.sensor)}, {"temp_unit", "K", FIELD(units.temp)},
          {"gyro_scale", "0.5", FIELD(units.gyro_scale)}, {"temp_scale", "2", FIELD(units.temp_scale)},
          {"temp_offset", "-3.5", FIELD(units.temp_offset)}, {"delimiter", "semicolon", FIELD(csv.delimiter)},
          {"decimal_comma", "true", FIELD(csv.decimal_comma)}, {"imu", "2", FIELD(imu)},
          {"rate", "+10", FIELD(csv.rate_hz), "10"}};
}

std::vector<RowCase<DataOptions>> data_cases(bool with_avg) {
  std::vector<RowCase<DataOptions>> cases = {{"deriv_span", "300", FIELD(pipeline.derivative_span_s)},
                                             {"sensor_tau", "20", FIELD(pipeline.sensor_tau_s)},
                                             {"causal", "true", FIELD(causal)},
                                             {"keep_outliers", "true", FIELD(keep_outliers)},
                                             {"outlier_threshold", "5", FIELD(outlier_threshold)}};
  if (with_avg) cases.push_back({"avg", "50", FIELD(pipeline.averaging.window_s)});
  return lift(cases, column_cases(), [](const DataOptions& o) -> const auto& { return o.pipeline.columns; });
}

std::vector<RowCase<ModelOptions>> model_cases() {
  return {{"model", "T + dT", FIELD(model)},
          {"add", "grad|lag", FIELD(add)},
          {"engine", "pso", FIELD(engine)},
          {"seed", "18446744073709551615", FIELD(seed)}};
}

TEST(OptionTable, FitRows) {
  using O = FitCommandOptions;
  std::vector<RowCase<O>> cases = {{"data", "d.csv", FIELD(data)},          {"budget", "-5", FIELD(budget)},
                                   {"target", "1e-3", FIELD(target), "0.001"}, {"option", "a=1|b=2", FIELD(engine_options)},
                                   {"output", "f.json", FIELD(output)},      {"json", "true", FIELD(json)}};
  expect_rows(fit_option_table(), lift(lift(cases, model_cases(), &O::model), data_cases(true), &O::data_options));
}

TEST(OptionTable, DiagnoseRows) {
  using O = DiagnoseCommandOptions;
  std::vector<RowCase<O>> cases = {{"data", "d.csv", FIELD(data)},
                                   {"candidates", "+supply_v,-grad", FIELD(candidates)},
                                   {"plots", "figs", FIELD(plots)},
                                   {"json", "true", FIELD(json)}};
  expect_rows(diagnose_option_table(), lift(lift(cases, model_cases(), &O::model), data_cases(true), &O::data_options));
}

TEST(OptionTable, AllanRows) {
  using O = AllanCommandOptions;
  std::vector<RowCase<O>> cases = {{"data", "d.csv", FIELD(request.data)},
                                   {"fit", "f.json", FIELD(request.fit_file)},
                                   {"taus", "decade", FIELD(taus)},
                                   {"tau_max", "1000", FIELD(request.options.tau_max_s)},
                                   {"ci", "0.95", FIELD(request.options.confidence)},
                                   {"plot", "a.png", FIELD(request.plot)},
                                   {"json", "true", FIELD(json)}};
  expect_rows(allan_option_table(), lift(cases, data_cases(false), &O::data_options));
}

TEST(OptionTable, CompensateRows) {
  using O = CompensateCommandOptions;
  std::vector<RowCase<O>> cases = {{"data", "d.csv", FIELD(request.data)},
                                   {"fit", "f.json", FIELD(request.fit_file)},
                                   {"output", "c.csv", FIELD(request.output)},
                                   {"causal", "true", FIELD(request.causal)},
                                   {"extrapolate", "true", FIELD(request.extrapolate)},
                                   {"json", "true", FIELD(json)}};
  expect_rows(compensate_option_table(),
              lift(cases, column_cases(), [](const O& o) -> const auto& { return o.request.columns; }));
  // Unset, the columns keep the fit's (ColumnMap::unset()).
  EXPECT_EQ(CompensateCommandOptions{}.request.columns.time, "");
}

TEST(OptionTable, ExportRows) {
  using O = ExportCommandOptions;
  expect_rows(export_option_table(),
              std::vector<RowCase<O>>{
                  {"fit", "f.json", FIELD(request.fit_file)}, {"format", "px4", FIELD(request.format)},
                  {"axes", "gz,-,gx", FIELD(request.axes)}, {"channel", "gx", FIELD(request.channel)},
                  {"prefix", "my", FIELD(request.prefix)}, {"instance", "3", FIELD(request.instance)},
                  {"device_id", "4294967296", FIELD(request.device_id)}, {"boot_temp", "-5", FIELD(request.boot_temp_c)},
                  {"drop_unsupported", "true", FIELD(request.drop_unsupported)},
                  {"accept_caution", "true", FIELD(request.accept_caution)}, {"data", "d.csv", FIELD(request.data)},
                  {"json", "true", FIELD(request.json)}, {"output", "p.params", FIELD(request.output)}});
}

TEST(OptionTable, SimulateRows) {
  using O = SimulateCommandOptions;
  expect_rows(simulate_option_table(),
              std::vector<RowCase<O>>{{"scenario", "s.toml", FIELD(request.scenario)}, {"rig", "r.toml", FIELD(request.rig)},
                                      {"gyro", "g.toml", FIELD(request.gyro)}, {"seed", "42", FIELD(request.seed)},
                                      {"hidden", "grad=0.02|T^3=1e-7", FIELD(request.hidden)},
                                      {"output", "o.csv", FIELD(request.output)}, {"plot", "p.png", FIELD(request.plot)},
                                      {"json", "true", FIELD(json)}});
}

TEST(OptionTable, PlanRows) {
  using O = PlanCommandOptions;
  expect_rows(plan_option_table(),
              std::vector<RowCase<O>>{
                  {"model", "T + lag", FIELD(request.model)},
                  {"se", "T=1e-3,dT=0.1|lag=2", FIELD(request.se), "T=1e-3|dT=0.1|lag=2"},
                  {"rel_se", "0.3", FIELD(request.rel_se)}, {"prior", "T=1", FIELD(request.prior)},
                  {"separate", "grad,lag=0.1", FIELD(request.separate), "grad|lag=0.1"},
                  {"param", "lag=1200", FIELD(request.param)}, {"scenario", "s.toml", FIELD(request.scenario)},
                  {"rig", "r.toml", FIELD(request.rig)}, {"gyro", "g.toml", FIELD(request.gyro)},
                  {"noise", "n.json", FIELD(request.noise)}, {"tau", "1800", FIELD(request.tau_s)},
                  {"range", "-20,50", FIELD(range), "-20|50"}, {"max_rate", "2.5", FIELD(request.max_rate_c_per_min)},
                  {"min_soak", "600", FIELD(request.min_soak_s)}, {"longest", "24", FIELD(request.longest_h)},
                  {"out", "p", FIELD(request.out)}, {"verify", "20", FIELD(request.verify)},
                  {"seed", "9", FIELD(request.seed)}, {"json", "true", FIELD(json)}});
  PlanCommandOptions o;  // --range takes its two numbers as one comma list or two values
  row_of(plan_option_table(), "range").set(o, "60");
  row_of(plan_option_table(), "range").set(o, "-40");
  EXPECT_EQ(text(o.range), "60|-40");
  expect_input_error([&] { row_of(plan_option_table(), "range").set(o, "1,x"); }, {"--range 'x': expected a number"});
}

TEST(OptionTable, ParsersRefuseWhatIsNotTheirKind) {
  expect_input_error([] { parse_number("--avg", ""); }, {"--avg '': expected a number"});
  expect_input_error([] { parse_number("--avg", "1.5s"); }, {"--avg '1.5s': expected a number"});
  EXPECT_EQ(parse_number("--avg", "1e2"), 100.0);
  EXPECT_EQ(parse_whole<int>("--verify", "+7"), 7);
  expect_input_error([] { parse_whole<std::uint64_t>("--seed", "-1"); }, {"--seed '-1': expected a whole number >= 0"});
  expect_input_error([] { parse_whole<int>("--verify", "99999999999"); },
                     {"--verify '99999999999': out of range (a whole number from -2147483648 to 2147483647)"});
  EXPECT_TRUE(parse_flag("--json", "true"));
  EXPECT_FALSE(parse_flag("--json", "false"));
  expect_input_error([] { parse_flag("--json", "maybe"); }, {"--json 'maybe': expected true or false"});
  EXPECT_EQ(keyword_of("-o,--output"), "output");
  EXPECT_EQ(keyword_of("--time-col"), "time_col");
  EXPECT_EQ(keyword_of("data"), "data");
  EXPECT_EQ(kind_name(OptionKind::list), "list");
}

TEST(OptionTable, KeywordsAreCheckedAsTheCommandLineChecksOptions) {
  FitCommandOptions o;
  apply_options(fit_option_table(), o, {{"data", "d.csv"}, {"avg", "50"}, {"add", "grad"}, {"add", "lag"}, {"causal", "true"}});
  EXPECT_EQ(o.data, "d.csv");
  EXPECT_EQ(o.data_options.pipeline.averaging.window_s, 50.0);
  EXPECT_EQ(text(o.model.add), "grad|lag");
  EXPECT_TRUE(o.data_options.causal);

  std::vector<std::string> keywords;
  for (const OptionInfo& r : list_options(fit_option_table())) keywords.push_back(r.keyword);
  FitCommandOptions unknown;
  expect_input_error([&] { apply_options(fit_option_table(), unknown, {{"data", "d.csv"}, {"avgg", "1"}}); },
                     {fmt::format("unknown option 'avgg' for fit; the options are: {}", fmt::join(keywords, ", "))});
  expect_input_error([&] { apply_options(fit_option_table(), unknown, {{"avg", "1"}}); },
                     {"fit: option 'data' is required"});
  expect_input_error([&] { apply_options(fit_option_table(), unknown, {{"data", "a"}, {"avg", "1"}, {"avg", "2"}}); },
                     {"fit: option 'avg' is given twice"});
  ExportCommandOptions e;
  expect_input_error([&] { apply_options(export_option_table(), e, {{"fit", "f.json"}, {"output", "x"}}); },
                     {"export: option 'format' is required"});
}

// The names `gyrotherm CMD --help` lists (the first word of each line of its
// Positionals and Options, -h,--help aside), in order.
std::vector<std::string> help_names(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream lines(help);
  bool in_list = false;
  const std::regex entry(R"(^  (\S+))");
  for (std::string line; std::getline(lines, line);) {
    if (line == "Positionals:" || line == "Options:") in_list = true;
    std::smatch m;
    if (in_list && std::regex_search(line, m, entry) && m[1] != "-h,--help") names.push_back(m[1]);
  }
  return names;
}

template <class O>
void expect_help_lists_the_table(const OptionTable<O>& table) {
  SCOPED_TRACE(table.command);
  ScratchDir dir;
  const CliResult r = run_cli(dir, table.command + " --help");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> positional, named;
  for (const OptionRow<O>& row : table.rows) {
    (row.names.starts_with('-') ? named : positional).push_back(row.names);
    EXPECT_NE(r.out.find(row.help), std::string::npos) << row.help;
    // The names, then what a value is ("--avg FLOAT", "--add TEXT", "data TEXT REQUIRED", "--json").
    const std::string shown = "\n  " + row.names + (row.value_name.empty() ? "" : " " + row.value_name) + " ";
    EXPECT_NE(r.out.find(shown), std::string::npos) << shown;
  }
  positional.insert(positional.end(), named.begin(), named.end());  // CLI11 lists the positionals first
  EXPECT_EQ(help_names(r.out), positional);
}

TEST(OptionTable, HelpListsExactlyEachTablesNamesAndHelp) {
  expect_help_lists_the_table(fit_option_table());
  expect_help_lists_the_table(diagnose_option_table());
  expect_help_lists_the_table(allan_option_table());
  expect_help_lists_the_table(compensate_option_table());
  expect_help_lists_the_table(export_option_table());
  expect_help_lists_the_table(simulate_option_table());
  expect_help_lists_the_table(plan_option_table());
  expect_help_lists_the_table(reproduce_option_table());
  expect_help_lists_the_table(score_option_table());
}

// Defaults are stated once: the struct's initialiser (or a row's note where
// the default is a rule, not a value), shown after the help as
// "(default: V)"; no help types one itself, where it could drift from the
// struct's.
template <class O>
void expect_defaults_from_the_struct(const OptionTable<O>& table) {
  SCOPED_TRACE(table.command);
  const std::regex typed(R"(\(default[ :]|; default |, default )");
  const O defaults{};
  const std::vector<OptionInfo> infos = list_options(table);
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    const OptionRow<O>& row = table.rows[k];
    EXPECT_FALSE(std::regex_search(row.help, typed)) << row.names << ": " << row.help;
    const OptionInfo& info = infos[k];
    if (!row.default_note.empty()) {
      EXPECT_EQ(info.default_value, row.default_note) << row.names;
    } else if (row.kind != OptionKind::flag && row.kind != OptionKind::list && !row.required && row.get) {
      const std::string value = row.get(defaults).value_or("");
      EXPECT_EQ(info.default_value, value.find(' ') == std::string::npos ? value : "'" + value + "'") << row.names;
    }
    // The rule, where the row has one, after the default.
    const std::string rule = row.rule ? "must be " + row.rule->text() : "";
    if (!info.default_value.empty()) {
      EXPECT_EQ(shown_help(info), row.help + " (default: " + info.default_value + (rule.empty() ? "" : "; " + rule) + ")");
    } else {
      EXPECT_EQ(shown_help(info), rule.empty() ? row.help : row.help + " (" + rule + ")");
    }
  }
}

TEST(OptionTable, EveryDefaultComesFromTheStructOrARowsNote) {
  expect_defaults_from_the_struct(fit_option_table());
  expect_defaults_from_the_struct(diagnose_option_table());
  expect_defaults_from_the_struct(allan_option_table());
  expect_defaults_from_the_struct(compensate_option_table());
  expect_defaults_from_the_struct(export_option_table());
  expect_defaults_from_the_struct(simulate_option_table());
  expect_defaults_from_the_struct(plan_option_table());
  expect_defaults_from_the_struct(check_option_table());
  expect_defaults_from_the_struct(report_option_table());
  expect_defaults_from_the_struct(reproduce_option_table());
  expect_defaults_from_the_struct(score_option_table());
  // What a user reads: fit's window is the struct's 100 s.
  const std::vector<OptionInfo> fit = list_options(fit_option_table());
  const auto avg = std::find_if(fit.begin(), fit.end(), [](const OptionInfo& i) { return i.names == "--avg"; });
  ASSERT_NE(avg, fit.end());
  EXPECT_EQ(shown_help(*avg), "Averaging window in seconds (the paper's 100 s averages) (default: 100)");
}

// docs/contracts.md lists every option of every command (its tables name
// each as `--name`, or `-o, --output`): an option added to a table and not
// to the contract fails here.
TEST(OptionTable, EveryOptionIsInTheContract) {
  const std::string contracts = testing::slurp(std::filesystem::path(GYROTHERM_SOURCE_DIR) / "docs" / "contracts.md");
  ASSERT_FALSE(contracts.empty());
  ASSERT_EQ(every_command_options().size(), 11u);  // the eleven commands
  for (const CommandOptions& c : every_command_options())
    for (const OptionInfo& row : c.rows) {
      if (!row.names.starts_with('-')) continue;  // a positional
      const std::string name = display_name(row.names);
      EXPECT_TRUE(contracts.find("`" + name) != std::string::npos || contracts.find(", " + name) != std::string::npos)
          << c.command << " " << name << " is not in docs/contracts.md";
    }
}

// docs/options.md is options_markdown()'s output, so the reference of every
// option, its value and its default cannot drift from the tables. With
// GYROTHERM_UPDATE_DOCS=1 the test writes the file instead of failing.
TEST(OptionTable, TheOptionsReferenceIsGenerated) {
  const std::filesystem::path file = std::filesystem::path(GYROTHERM_SOURCE_DIR) / "docs" / "options.md";
  const std::string expected = options_markdown();
  if (const char* update = std::getenv("GYROTHERM_UPDATE_DOCS"); update != nullptr && std::string(update) == "1") {
    std::ofstream(file, std::ios::binary) << expected;
    GTEST_SKIP() << "wrote " << file;
  }
  const std::string written = testing::slurp(file);
  EXPECT_TRUE(written == expected) << file
                                   << " differs from the option tables; run this test with GYROTHERM_UPDATE_DOCS=1 "
                                      "to write it";
  // Every command's every option is in it, with its default.
  for (const CommandOptions& c : every_command_options()) {
    EXPECT_NE(written.find("\n## " + c.command + "\n"), std::string::npos) << c.command;
    for (const OptionInfo& row : c.rows) {
      if (!row.default_value.empty()) {
        EXPECT_NE(written.find(" | " + row.default_value), std::string::npos) << c.command << " " << row.names;
      }
      if (row.rule) {
        EXPECT_NE(written.find(" | " + row.rule->text() + " | "), std::string::npos) << row.names;
      }
    }
  }
  // And every engine's every option, with its default and rule.
  for (const fit::EngineInfo& e : fit::engine_registry())
    for (const OptionInfo& row : e.options)
      EXPECT_NE(written.find(fmt::format("| {} | `{}` | {} | {} |", e.name, row.keyword, row.default_value,
                                         row.rule->text())),
                std::string::npos)
          << e.name << " " << row.keyword;
}

// A repeatable option takes one value per name, so that the positional after
// it is never taken for a second value; plan's --range takes its two.
TEST(OptionTable, ARepeatableOptionBeforeThePositionalTakesOneValue) {
  ScratchDir dir;
  const std::string scenario = std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/cycle.toml";
  const CliResult score = run_cli(dir, "score --budget 50 " + scenario + " --trials 1 --engines ols,afsa --json");
  ASSERT_EQ(score.exit_code, 0) << score.err;
  EXPECT_EQ(nlohmann::json::parse(score.out)["trials"], 1);
  const CliResult two = run_cli(dir, "score " + scenario + " --budget 50 60 --trials 1");
  EXPECT_EQ(two.exit_code, 2);
  EXPECT_NE(two.err.find("60"), std::string::npos) << two.err;
  // (No test of an hour meets the default precision: the refusal names the limits read.)
  const CliResult range = run_cli(dir, "plan --range -10 40 --longest 1 --out p");
  EXPECT_NE(range.err.find("at these limits (-10..40 °C"), std::string::npos) << range.err;
}

}  // namespace
}  // namespace gyrotherm::studies
