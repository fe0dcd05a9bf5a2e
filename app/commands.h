#pragma once
// Each subcommand lives in its own file and registers itself on the CLI11 app.
// When the user picks it, *run is set to what executes it; run returns the
// process exit code (0 success, 1 failed check, 2 bad input; InputError thrown
// from inside is turned into 2 by main).

#include <functional>

namespace CLI {
class App;
}

namespace gyrotherm::app {

using Run = std::function<int()>;

void add_simulate_command(CLI::App& app, Run* run);
void add_fit_command(CLI::App& app, Run* run);
void add_compensate_command(CLI::App& app, Run* run);
void add_registry_commands(CLI::App& app, Run* run);
void add_diagnose_command(CLI::App& app, Run* run);
void add_reproduce_command(CLI::App& app, Run* run);
void add_score_command(CLI::App& app, Run* run);
void add_allan_command(CLI::App& app, Run* run);
void add_export_command(CLI::App& app, Run* run);

}  // namespace gyrotherm::app
