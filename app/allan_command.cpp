// gyrotherm allan DATA.csv [--fit FIT.json] [--taus octave|decade|all] [--tau-max S]
//                          [--ci C] [--plot PNG] [--json]
// (studies/allan/allan_study.h)

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <map>

#include "app/commands.h"
#include "app/pipeline_options.h"
#include "sim/util/input_error.h"
#include "studies/allan/allan_study.h"

namespace gyrotherm::app {
namespace {

struct AllanCli {
  studies::AllanRequest request;
  std::string taus = "octave";
  bool json = false;
  DataOptions data_options;
};

int run_allan(AllanCli o) {
  static const std::map<std::string, studies::TauSpacing> kSpacing = {{"octave", studies::TauSpacing::octave},
                                                                      {"decade", studies::TauSpacing::decade},
                                                                      {"all", studies::TauSpacing::all}};
  const auto spacing = kSpacing.find(o.taus);
  if (spacing == kSpacing.end()) throw InputError(fmt::format("--taus {}: expected octave, decade or all", o.taus));
  studies::AllanOptions& options = o.request.options;
  options.spacing = spacing->second;
  if (options.tau_max_s < 0.0)
    throw InputError(fmt::format("--tau-max {}: expected a positive time in seconds", options.tau_max_s));
  if (!(options.confidence > 0.0 && options.confidence < 1.0))
    throw InputError(
        fmt::format("--ci {}: the confidence must be between 0 and 1 (e.g. 0.68 or 0.95)", options.confidence));
  if (o.request.fit_file.empty()) o.request.pipeline = o.data_options.resolved();  // with a fit: the fit's
  const std::vector<studies::AllanStudy> studies = studies::run_allan(o.request);
  fmt::print("{}", o.json ? studies::allan_json(studies).dump() + "\n" : studies::allan_text(studies));
  return 0;
}

}  // namespace

void add_allan_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<AllanCli>();
  CLI::App* cmd = app.add_subcommand(
      "allan", "Allan deviation with intervals and noise coefficients, before and after compensation");
  cmd->add_option("data", o->request.data, "Measurement CSV, or a PX4 ULog / ArduPilot DataFlash log")->required();
  cmd->add_option("--fit", o->request.fit_file,
                  "Also the output compensated by this saved fit (as compensate --causal), side by side");
  cmd->add_option("--taus", o->taus, "τ set: octave (default: 1, 2, 4, … samples), decade, or all");
  cmd->add_option("--tau-max", o->request.options.tau_max_s,
                  "Longest τ in seconds (default a quarter of the record; it needs a gap-free stretch of 2τ)");
  cmd->add_option("--ci", o->request.options.confidence,
                  "Confidence of the intervals, between 0 and 1 (default 0.683, ±1σ)");
  cmd->add_option("--plot", o->request.plot, "Write the log-log figure (PNG) with bands and the coefficients read");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  add_data_options(cmd, o->data_options, false);
  when_chosen(cmd, run, [o] { return run_allan(*o); });
}

}  // namespace gyrotherm::app
