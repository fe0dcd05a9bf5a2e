#include "studies/options/option_reference.h"

#include <fmt/format.h>

#include "fit/engines/engine.h"
#include "studies/options/allan_options.h"
#include "studies/options/check_options.h"
#include "studies/options/compensate_options.h"
#include "studies/options/diagnose_options.h"
#include "studies/options/export_options.h"
#include "studies/options/fit_options.h"
#include "studies/options/plan_options.h"
#include "studies/options/report_options.h"
#include "studies/options/reproduce_options.h"
#include "studies/options/score_options.h"
#include "studies/options/simulate_options.h"

namespace gyrotherm::studies {

namespace {

template <class Options>
CommandOptions listed(const OptionTable<Options>& table) {
  return {table.command, list_options(table)};
}

// A Markdown table cell: '|' escaped, line breaks as spaces.
std::string cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|') out += "\\|";
    else out += c == '\n' ? ' ' : c;
  }
  return out;
}

}  // namespace

const std::vector<CommandOptions>& every_command_options() {
  static const std::vector<CommandOptions> all = {
      listed(reproduce_option_table()), listed(simulate_option_table()),   listed(fit_option_table()),
      listed(diagnose_option_table()),  listed(allan_option_table()),      listed(compensate_option_table()),
      listed(check_option_table()),     listed(export_option_table()),     listed(plan_option_table()),
      listed(report_option_table()),    listed(score_option_table())};
  return all;
}

const CommandOptions* command_options(const std::string& command) {
  for (const CommandOptions& c : every_command_options())
    if (c.command == command) return &c;
  return nullptr;
}

std::string options_markdown() {
  std::string out =
      "# Options of every command\n\n"
      "Generated from the commands' option tables (`studies/options/`) by\n"
      "`options_markdown()`; do not edit by hand: `GYROTHERM_UPDATE_DOCS=1\n"
      "build/tests/gyrotherm_tests --gtest_filter=OptionTable.TheOptionsReferenceIsGenerated`\n"
      "rewrites it after a table changes. `gyrotherm COMMAND --help` shows the\n"
      "same rows; docs/contracts.md says what each command does with them.\n";
  for (const CommandOptions& c : every_command_options()) {
    out += fmt::format("\n## {}\n\n| option | value | default | must be | what it is |\n|---|---|---|---|---|\n",
                       c.command);
    for (const OptionInfo& r : c.rows) {
      const bool positional = !r.names.starts_with('-');
      std::string value = r.kind == OptionKind::flag ? std::string() : r.value_name;
      if (r.kind == OptionKind::list && !r.several_per_name) value += " (repeatable)";
      std::string dflt = r.required ? "required" : r.default_value;
      out += fmt::format("| {} | {} | {} | {} | {} |\n", positional ? r.names : "`" + r.names + "`", cell(value),
                         cell(dflt), cell(r.rule ? r.rule->text() : ""), cell(r.help));
    }
  }
  out +=
      "\n## engine options\n\n"
      "Each engine's `--option KEY=VALUE` (fit, diagnose, score's `ENGINE:KEY=VALUE`), from the same kind of\n"
      "table in the engine's file; `gyrotherm engines` lists them too.\n\n"
      "| engine | key | default | must be | what it is |\n|---|---|---|---|---|\n";
  for (const fit::EngineInfo& e : fit::engine_registry())
    for (const OptionInfo& r : e.options)
      out += fmt::format("| {} | `{}` | {} | {} | {} |\n", e.name, r.keyword, cell(r.default_value),
                         cell(r.rule ? r.rule->text() : ""), cell(r.help));
  return out;
}

}  // namespace gyrotherm::studies
