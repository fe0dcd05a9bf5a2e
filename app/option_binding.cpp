// The one file that includes CLI11 (app/commands.h): the app, its
// subcommands and their options.

#include "app/option_binding.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>
#include <nlohmann/json.hpp>

namespace gyrotherm::app {

namespace {

// Edits (insert, delete, substitute, swap two neighbours) from a to b.
std::size_t edits(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// " (did you mean 'fit'?)" for a word within two edits of one name (and
// fewer than half its letters), else "".
std::string did_you_mean(std::string_view typed, const std::vector<std::string>& names) {
  std::string best;
  std::size_t fewest = 3;
  for (const std::string& n : names)
    if (const std::size_t e = edits(typed, n); e < fewest && 2 * e < typed.size()) fewest = e, best = n;
  return best.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", best);
}

// What a parse error cannot say: the command or option a typo was meant to be.
std::string typo_hint(CLI::App& app, int argc, char** argv) {
  if (argc < 2) return {};
  std::vector<std::string> commands;
  for (const CLI::App* c : app.get_subcommands([](const CLI::App*) { return true; })) commands.push_back(c->get_name());
  const std::string first = argv[1];
  if (!first.starts_with('-') && std::find(commands.begin(), commands.end(), first) == commands.end())
    return fmt::format("'{}' is no command{}; the commands: {}", first, did_you_mean(first, commands),
                       fmt::join(commands, ", "));
  for (const CLI::App* chosen : app.get_subcommands()) {
    std::vector<std::string> options;
    for (const CLI::Option* o : chosen->get_options())
      for (const std::string& l : o->get_lnames()) options.push_back("--" + l);
    for (int k = 2; k < argc; ++k) {
      const std::string word = std::string(argv[k]).substr(0, std::string(argv[k]).find('='));
      if (word.starts_with("--") && std::find(options.begin(), options.end(), word) == options.end())
        if (const std::string hint = did_you_mean(word, options); !hint.empty())
          return fmt::format("{} is no option of {}{}", word, chosen->get_name(), hint);
    }
  }
  return {};
}

}  // namespace

int parse_command_line(int argc, char** argv, Run* run) {
  // Static: the chosen command reads its options' counts and values when it
  // runs, after this returns.
  static CLI::App app{"gyrotherm: thermal-test simulator and fitting benchmark for the temperature compensation of gyro "
               "bias"};
  app.require_subcommand(1);
#define COMMAND(name) add_##name##_command(app, run);
#include "app/commands.def"
#undef COMMAND
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    const std::string hint = typo_hint(app, argc, argv);
    fmt::print(stderr, "gyrotherm: {}{}\nRun 'gyrotherm --help' for the commands and options.\n", e.what(),
               hint.empty() ? "" : "\ngyrotherm: " + hint);
    return 2;
  }
  return -1;
}

int print_report(bool as_json, const nlohmann::ordered_json& json, const std::string& text) {
  fmt::print("{}", as_json ? json.dump() + "\n" : text);
  return 0;
}

CLI::App* add_subcommand(CLI::App& app, const std::string& name, const std::string& description) {
  return app.add_subcommand(name, description);
}

void when_chosen(CLI::App* command, Run* run, Run work) {
  command->callback([run, work = std::move(work)] { *run = work; });
}

void add_listing_command(CLI::App& app, Run* run, const std::string& name, const std::string& description,
                         std::string (*text)(), nlohmann::ordered_json (*json)()) {
  auto as_json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(name, description);
  cmd->add_flag("--json", *as_json, "Print one JSON object");
  when_chosen(cmd, run, [=] {
    fmt::print("{}", *as_json ? json().dump() + "\n" : text());
    return 0;
  });
}

std::function<GivenValues()> add_rows(CLI::App* command, const std::vector<OptionInfo>& rows) {
  struct Slot {
    CLI::Option* option = nullptr;
    OptionKind kind = OptionKind::text;
    bool flag = false;
    std::string text;
    std::vector<std::string> list;
  };
  auto slots = std::make_shared<std::vector<Slot>>(rows.size());  // never resized: CLI11 keeps their addresses
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const OptionInfo& row = rows[i];
    Slot& slot = (*slots)[i];
    slot.kind = row.kind;
    if (row.kind == OptionKind::flag) {
      slot.option = command->add_flag(row.names, slot.flag, shown_help(row));
    } else if (row.kind == OptionKind::list) {
      slot.option = command->add_option(row.names, slot.list, shown_help(row));
      // one value per name, so that a positional after it is never taken for one
      slot.option->allow_extra_args(row.several_per_name);
      slot.option->option_text(row.value_name + (row.required ? " REQUIRED" : ""));
    } else {
      slot.option = command->add_option(row.names, slot.text, shown_help(row))->type_name(row.value_name);
    }
    if (row.required) slot.option->required();
  }
  return [slots] {
    GivenValues given;
    for (std::size_t i = 0; i < slots->size(); ++i) {
      const Slot& slot = (*slots)[i];
      if (slot.option->count() == 0) continue;
      if (slot.kind == OptionKind::flag)
        given.emplace_back(i, slot.flag ? "true" : "false");
      else if (slot.kind == OptionKind::list)
        for (const std::string& value : slot.list) given.emplace_back(i, value);
      else
        given.emplace_back(i, slot.text);
    }
    return given;
  };
}

}  // namespace gyrotherm::app
