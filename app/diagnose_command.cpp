// gyrotherm diagnose DATA.csv [--model F] [--add TERM ...] [--candidates LIST] [--plots DIR] [--json] …

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "app/commands.h"
#include "app/pipeline_options.h"
#include "app/progress.h"
#include "sim/util/comma_list.h"
#include "studies/diagnose/diagnose_run.h"

namespace gyrotherm::app {
namespace {

struct DiagnoseCli {
  std::string data;
  ModelOptions model;
  std::string candidates;
  std::string plots;
  bool json = false;
  DataOptions data_options;
};

int run_diagnose(const DiagnoseCli& o) {
  studies::DiagnoseRequest request;
  request.data = o.data;
  request.base_terms = o.model.base_terms();
  request.terms = o.model.terms();
  request.added = o.model.add;
  request.engine = o.model.engine;
  request.settings.seed = o.model.seed;
  fit::find_engine(request.engine).make(request.settings);  // the engine's errors before the data options'
  request.pipeline = o.data_options.resolved();
  request.options.candidates = split_commas(o.candidates);
  request.plots = o.plots;
  request.progress = step_progress();
  const studies::DiagnoseRun run = studies::run_diagnose(request);
  fmt::print("{}", o.json ? studies::diagnose_json(run).dump() + "\n" : studies::diagnose_text(run));
  return 0;
}

}  // namespace

void add_diagnose_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<DiagnoseCli>();
  CLI::App* cmd = app.add_subcommand(
      "diagnose", "Where a bias model fails on measurements, and which physical effect is missing");
  cmd->add_option("data", o->data, "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log")->required();
  add_model_options(cmd, o->model, "Add a term and compare before/after (repeatable)");
  cmd->add_option("--candidates", o->candidates,
                  "Candidates to try: a comma list (terms, columns, 'step'), or +NAME/-NAME to add to or "
                  "remove from the default set (every other term, every numeric column, the steps found)");
  cmd->add_option("--plots", o->plots, "Write PNG figures into this folder");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  add_data_options(cmd, o->data_options);
  when_chosen(cmd, run, [o] { return run_diagnose(*o); });
}

}  // namespace gyrotherm::app
