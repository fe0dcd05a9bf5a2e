// gyrotherm fit DATA.csv [--model F] [--engine E] [--seed N] [--avg SECONDS]
//                        [--budget N] [--target SIGMA] [--option KEY=VALUE ...]
//                        [-o FIT.json] [--json]
// (studies/fit/fit_run.h)

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "app/commands.h"
#include "app/pipeline_options.h"
#include "studies/fit/fit_run.h"

namespace gyrotherm::app {
namespace {

struct FitCli {
  std::string data;
  ModelOptions model;
  long budget = 0;
  double target = 0.0;
  std::vector<std::string> engine_options;
  std::string output;
  bool json = false;
  DataOptions data_options;
};

int run_fit(const FitCli& o) {
  studies::FitRequest request;
  request.data = o.data;
  request.terms = o.model.terms();
  request.engine = o.model.engine;
  const fit::EngineInfo& engine = fit::find_engine(request.engine);  // its errors first, then the options'
  request.settings = fit::engine_settings(o.model.seed, o.budget, o.target, o.engine_options);
  engine.make(request.settings);
  request.pipeline = o.data_options.resolved();
  request.output = o.output;
  const studies::FitRun run = studies::run_fit(request);
  fmt::print("{}", o.json ? run.json : studies::fit_text(run));
  return 0;
}

}  // namespace

void add_fit_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<FitCli>();
  CLI::App* cmd = app.add_subcommand("fit", "Fit a bias model to measurements (CSV)");
  cmd->add_option("data", o->data, "Measurement CSV (time_s, temp_c, gyro_dph[, temp2_c]), or a PX4 / ArduPilot log")->required();
  add_model_options(cmd, o->model, "Add a term to the model (repeatable)");
  cmd->add_option("--budget", o->budget, "Maximum objective evaluations (0: the engine's default)");
  cmd->add_option("--target", o->target, "Stop when sigma <= this, °/h (0: none)");
  cmd->add_option("--option", o->engine_options, "Engine option KEY=VALUE (repeatable)");
  cmd->add_option("-o,--output", o->output, "Save the fit as JSON (for compensate)");
  cmd->add_flag("--json", o->json, "Print the fit as one JSON object");
  add_data_options(cmd, o->data_options);
  when_chosen(cmd, run, [o] { return run_fit(*o); });
}

}  // namespace gyrotherm::app
