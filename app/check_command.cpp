// gyrotherm check LOG --params FILE [--max-residual X] [--json]
// (studies/options/check_options.h, studies/check/check_run.h): exit 1 when
// the residual exceeds --max-residual, 0 otherwise, 2 on bad input.

#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/check_options.h"

namespace gyrotherm::app {

void add_check_command(CLI::App& app, Run* run) {
  add_table_command<studies::CheckCommandOptions>(app, run, "check", "Check a calibration on another log, as the firmware applies it",
      studies::check_option_table(), [](const auto& o) {
    const studies::CheckResult r = studies::run_check(studies::check_request(o));
    const int printed = print_report(o.json, studies::check_json(r), studies::check_text(r));
    return printed != 0 ? printed : r.exit_code();
  });
}

}  // namespace gyrotherm::app
