// gyrotherm fit DATA.csv [--model F] [--engine E] [--seed N] [--avg SECONDS]
//                        [--budget N] [--target SIGMA] [--option KEY=VALUE ...]
//                        [-o FIT.json] [--json]
// (studies/options/fit_options.h, studies/fit/fit_run.h)

#include <fmt/core.h>

#include "app/option_binding.h"
#include "studies/options/fit_options.h"

namespace gyrotherm::app {

void add_fit_command(CLI::App& app, Run* run) {
  add_table_command<studies::FitCommandOptions>(app, run, "fit", "Fit a bias model to measurements (CSV, PX4 ULog, ArduPilot DataFlash)",
      studies::fit_option_table(), [](const auto& o) {
    studies::FitRequest request = studies::fit_request(o);
    request.hash_data = o.json || !o.output.empty();  // the text report alone has no use for the hash
    const studies::FitRun r = studies::run_fit(request);
    fmt::print("{}", o.json ? r.json : studies::fit_text(r));
    return 0;
  });
}

}  // namespace gyrotherm::app
