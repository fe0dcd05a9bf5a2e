#pragma once
// Each subcommand lives in its own file, app/NAME_command.cpp, and registers
// itself on the CLI11 app; app/commands.def lists them. When the user picks
// one, *run is set to what executes it; run returns the process exit code
// (0 success, 1 failed check, 2 bad input; InputError thrown from inside is
// turned into 2 by main).

#include <functional>
#include <string>

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

// When the user picks `command`, *run becomes `work`.
void when_chosen(CLI::App* command, Run* run, Run work);

// A command that lists a registry: NAME [--json], printing text() or json().
void add_listing_command(CLI::App& app, Run* run, const std::string& name, const std::string& description,
                         std::function<std::string()> text, std::function<std::string()> json);

}  // namespace gyrotherm::app
