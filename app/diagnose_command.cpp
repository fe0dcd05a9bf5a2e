// gyrotherm diagnose DATA.csv [--model F] [--add TERM ...] [--candidates LIST] [--plots DIR] [--json] …
// (studies/options/diagnose_options.h, studies/diagnose/diagnose_run.h)

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "app/progress.h"
#include "studies/options/diagnose_options.h"

namespace gyrotherm::app {

void add_diagnose_command(CLI::App& app, Run* run) {
  add_table_command<studies::DiagnoseCommandOptions>(app, run, "diagnose", "Where a bias model fails on measurements, and which physical effect is missing",
      studies::diagnose_option_table(), [](const auto& o) {
    studies::DiagnoseRequest request = studies::diagnose_request(o);
    request.progress = step_progress();
    const studies::DiagnoseRun r = studies::run_diagnose(request);
    fmt::print("{}", o.json ? studies::diagnose_json(r).dump() + "\n" : studies::diagnose_text(r));
    return 0;
  });
}

}  // namespace gyrotherm::app
