// gyrotherm — thermal-test simulator and benchmark suite for the temperature
// compensation of gyro bias. README.md shows the commands; docs/contracts.md
// is the command-line contract.

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "sim/cvode_solver.h"
#include "sim/util/atomic_file.h"
#include "sim/util/input_error.h"

namespace gyrotherm::app {

void when_chosen(CLI::App* command, Run* run, Run work) {
  command->callback([run, work = std::move(work)] { *run = work; });
}

void add_listing_command(CLI::App& app, Run* run, const std::string& name, const std::string& description,
                         std::function<std::string()> text, std::function<std::string()> json) {
  auto as_json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(name, description);
  cmd->add_flag("--json", *as_json, "Print one JSON object");
  when_chosen(cmd, run, [=] {
    fmt::print("{}", *as_json ? json() : text());
    return 0;
  });
}

}  // namespace gyrotherm::app

int main(int argc, char** argv) {
  CLI::App app{"gyrotherm: thermal-test simulator and fitting benchmark for the temperature compensation of gyro "
               "bias"};
  app.require_subcommand(1);
  gyrotherm::app::Run run;
#define COMMAND(name) gyrotherm::app::add_##name##_command(app, &run);
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
    fmt::print(stderr, "gyrotherm: {}\nRun 'gyrotherm --help' for the commands and options.\n", e.what());
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
               "Check the rig's capacities and conductances for values far outside the physical range.\n",
               e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "gyrotherm: internal error: {}\n", e.what());
    return 3;
  }
}
