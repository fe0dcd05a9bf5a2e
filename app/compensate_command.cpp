// gyrotherm compensate DATA.csv --fit FIT.json [-o OUT.csv] [--causal] [--json]
// (studies/options/compensate_options.h, studies/fit/compensate_run.h)

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/option_binding.h"
#include "studies/options/compensate_options.h"

namespace gyrotherm::app {

void add_compensate_command(CLI::App& app, Run* run) {
  CLI::App* cmd = add_subcommand(app, "compensate", "Apply a saved fit to other data");
  bind_command<studies::CompensateCommandOptions>(cmd, run, studies::compensate_option_table(), [](const auto& o) {
    const studies::CompensateRun r = studies::run_compensate(studies::compensate_request(o));
    fmt::print("{}", o.json ? studies::compensate_json(r).dump() + "\n" : studies::compensate_text(r));
    return 0;
  });
}

}  // namespace gyrotherm::app
