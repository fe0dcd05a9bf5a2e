// gyrotherm compensate DATA.csv --fit FIT.json [-o OUT.csv] [--causal] [--json]
// (studies/fit/compensate_run.h)

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "app/commands.h"
#include "app/pipeline_options.h"
#include "studies/fit/compensate_run.h"

namespace gyrotherm::app {

void add_compensate_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<studies::CompensateRequest>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("compensate", "Apply a saved fit to other data");
  cmd->add_option("data", o->data, "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log")->required();
  cmd->add_option("--fit", o->fit_file, "Fit saved by 'gyrotherm fit -o'")->required();
  cmd->add_option("-o,--output", o->output, "Write time_s, temp_c, gyro_dph, model_dph, compensated_dph, outlier");
  cmd->add_flag("--causal", o->causal, "Real-time compensation: backward differences and only past windows");
  cmd->add_flag("--json", *json, "Print one JSON object");
  add_column_options(cmd, o->columns, /*fit_defaults=*/true);
  when_chosen(cmd, run, [o, json] {
    const studies::CompensateRun r = studies::run_compensate(*o);
    fmt::print("{}", *json ? studies::compensate_json(r).dump() + "\n" : studies::compensate_text(r));
    return 0;
  });
}

}  // namespace gyrotherm::app
