// gyrotherm compensate DATA.csv --fit FIT.json [-o OUT.csv] [--causal] [--json]
// (studies/options/compensate_options.h, studies/fit/compensate_run.h)

#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/compensate_options.h"

namespace gyrotherm::app {

void add_compensate_command(CLI::App& app, Run* run) {
  add_table_command<studies::CompensateCommandOptions>(app, run, "compensate", "Apply a saved fit to other data",
      studies::compensate_option_table(), [](const auto& o) {
    const studies::CompensateRun r = studies::run_compensate(studies::compensate_request(o));
    return print_report(o.json, studies::compensate_json(r), studies::compensate_text(r));
  });
}

}  // namespace gyrotherm::app
