#pragma once
// Each subcommand lives in its own file, app/NAME_command.cpp, and registers
// itself on the CLI11 app; app/commands.def lists them. When the user picks
// one, *run is set to what executes it; run returns the process exit code
// (0 success, 1 failed check, 2 bad input; InputError thrown from inside is
// turned into 2 by main). CLI11 itself is included by app/option_binding.cpp
// alone (its header costs ~10 s of compiling per file): the command files
// reach it through the functions declared here and in app/option_binding.h.

#include <functional>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace CLI {
class App;
}

namespace gyrotherm::app {

using Run = std::function<int()>;

#define COMMAND(name) void add_##name##_command(CLI::App& app, Run* run);
#include "app/commands.def"
#undef COMMAND

// The shipped scenarios: ./scenarios when run from the source tree, else the
// source tree's (reproduce's and plan's defaults).
std::string default_scenarios_dir();

// Parses the command line: every command of app/commands.def on one CLI11
// app, which lives until the program ends (*run reads from it). Call once.
// Returns -1 when *run is to be run, else the exit code (0 after --help, 2
// for a command line that does not parse, with its message).
int parse_command_line(int argc, char** argv, Run* run);

// A subcommand of `app`.
CLI::App* add_subcommand(CLI::App& app, const std::string& name, const std::string& description);

// When the user picks `command`, *run becomes `work`.
void when_chosen(CLI::App* command, Run* run, Run work);

// What a command prints: `json` (one line) with --json, else `text`; returns 0.
int print_report(bool as_json, const nlohmann::ordered_json& json, const std::string& text);

// A command that lists a registry: NAME [--json], printing text() or json()'s one line.
void add_listing_command(CLI::App& app, Run* run, const std::string& name, const std::string& description,
                         std::string (*text)(), nlohmann::ordered_json (*json)());

}  // namespace gyrotherm::app
