// gyrotherm — thermal-test simulator and benchmark suite for the temperature
// compensation of gyro bias. README.md shows the commands; docs/contracts.md
// is the command-line contract. The command line is parsed in
// app/option_binding.cpp; here the chosen command runs and its errors become
// exit codes.

#include <fmt/core.h>

#include <exception>

#include "app/commands.h"
#include "sim/cvode_solver.h"
#include "sim/util/atomic_file.h"
#include "sim/util/huge_pages.h"
#include "sim/util/input_error.h"

int main(int argc, char** argv) {
  gyrotherm::prefer_huge_pages();
  gyrotherm::app::Run run;
  if (const int code = gyrotherm::app::parse_command_line(argc, argv, &run); code >= 0) return code;

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
