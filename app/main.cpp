// gyrotherm — thermal-test simulator and benchmark suite for the temperature
// compensation of ring laser gyro bias. See README.md and ../shared/DESIGN.md
// for the command-line contract.

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "sim/util/atomic_file.h"
#include "sim/cvode_solver.h"
#include "sim/util/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"gyrotherm: thermal-test simulator and fitting benchmark for RLG bias "
               "temperature compensation"};
  app.require_subcommand(1);
  gyrotherm::app::Run run;
  gyrotherm::app::add_simulate_command(app, &run);
  gyrotherm::app::add_fit_command(app, &run);
  gyrotherm::app::add_compensate_command(app, &run);
  gyrotherm::app::add_registry_commands(app, &run);
  gyrotherm::app::add_diagnose_command(app, &run);
  gyrotherm::app::add_reproduce_command(app, &run);
  gyrotherm::app::add_score_command(app, &run);
  gyrotherm::app::add_allan_command(app, &run);
  gyrotherm::app::add_export_command(app, &run);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    std::fputs(app.help("", CLI::AppFormatMode::All).c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "gyrotherm: {}\nRun 'gyrotherm --help' for the commands and options.\n",
               e.what());
    return 2;
  }

  gyrotherm::install_interrupt_cleanup();
  try {
    return run();
  } catch (const gyrotherm::InputError& e) {
    fmt::print(stderr, "gyrotherm: error: {}\n", e.what());
    return 2;
  } catch (const gyrotherm::sim::SolverError& e) {
    fmt::print(stderr,
               "gyrotherm: error: the thermal simulation failed: {}\n"
               "Check the rig's capacities and conductances for values far outside the "
               "physical range.\n",
               e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "gyrotherm: internal error: {}\n", e.what());
    return 3;
  }
}
