// gyrotherm report LOG [--fit FILE | --model F] [--params FILE] -o report.html
// (studies/options/report_options.h, studies/report/report.h)

#include <fmt/core.h>

#include "app/option_binding.h"
#include "app/progress.h"
#include "studies/options/report_options.h"

namespace gyrotherm::app {

void add_report_command(CLI::App& app, Run* run) {
  add_table_command<studies::ReportCommandOptions>(app, run, "report", "One self-contained HTML page (and its JSON twin) to share a calibration",
      studies::report_option_table(), [](const auto& o) {
    studies::ReportRequest request = studies::report_request(o);
    request.progress = step_progress();  // each study in turn, on stderr
    fmt::print("{}", studies::run_report(request).text);  // the files written
    return 0;
  });
}

}  // namespace gyrotherm::app
