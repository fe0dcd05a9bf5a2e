// gyrotherm allan DATA.csv [--fit FIT.json] [--taus octave|decade|all] [--tau-max S]
//                          [--ci C] [--plot PNG] [--json]
// The Allan deviation of the gyro output with intervals and noise
// coefficients, before and after a saved fit (studies/allan/allan_study.h).

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <map>

#include "app/commands.h"
#include "app/pipeline_options.h"
#include "fit/fit_file.h"
#include "fit/pipeline.h"
#include "sim/util/input_error.h"
#include "studies/allan/allan_study.h"

namespace gyrotherm::app {
namespace {

struct AllanCommandOptions {
  std::string data;
  std::string fit_file;
  std::string taus = "octave";
  double ci = 0.6827;
  double tau_max = 0.0;
  std::string plot;
  bool json = false;
  DataOptions data_options;
};

int run_allan(const AllanCommandOptions& o) {
  static const std::map<std::string, studies::TauSpacing> kSpacing = {
      {"octave", studies::TauSpacing::octave}, {"decade", studies::TauSpacing::decade}, {"all", studies::TauSpacing::all}};
  const auto spacing = kSpacing.find(o.taus);
  if (spacing == kSpacing.end())
    throw InputError(fmt::format("--taus {}: expected octave, decade or all", o.taus));
  studies::AllanOptions options;
  options.spacing = spacing->second;
  options.confidence = o.ci;
  options.tau_max_s = o.tau_max;
  if (o.tau_max < 0.0) throw InputError(fmt::format("--tau-max {}: expected a positive time in seconds", o.tau_max));
  if (!(o.ci > 0.0 && o.ci < 1.0))
    throw InputError(fmt::format("--ci {}: the confidence must be between 0 and 1 (e.g. 0.68 or 0.95)", o.ci));

  std::vector<studies::AllanStudy> studies;
  if (!o.fit_file.empty()) {
    // Every channel the fit holds, read with the fit's own columns and units.
    for (const fit::SavedFit& fit : fit::load_fits(o.fit_file)) {
      const fit::PipelineOptions pipeline = fit::reading_columns_of(fit.pipeline, fit.terms);
      try {
        const fit::Measurement m = fit::read_measurement_csv(o.data, pipeline.columns);
        studies.push_back(studies::allan_study(m, &fit, options));
      } catch (const InputError& e) {
        throw InputError(fmt::format("{}{} with the fit {}: {}", o.data,
                                     fit.channel.empty() ? "" : ", channel " + fit.channel, o.fit_file, e.what()));
      }
    }
  } else {
    const auto channels = o.data_options.channels();
    studies = for_each_channel(channels, o.data_options.resolved(),
                               [&](const std::string& channel, const fit::PipelineOptions& p) {
                                 studies::AllanStudy s =
                                     studies::allan_study(fit::read_measurement_csv(o.data, p.columns), nullptr, options);
                                 if (channels.size() > 1) s.channel = channel;
                                 return s;
                               });
  }
  if (!o.plot.empty()) {
    for (std::size_t i = 0; i < studies.size(); ++i) {
      std::filesystem::path png = o.plot;
      if (studies.size() > 1)
        png.replace_filename(png.stem().string() + "_" + studies[i].channel + png.extension().string());
      studies::write_allan_plot(png, studies[i]);
    }
  }
  if (o.json) {
    if (studies.size() == 1) {
      fmt::print("{}\n", studies::allan_json(studies.front()).dump());
    } else {
      nlohmann::ordered_json all = nlohmann::ordered_json::array();
      for (const auto& s : studies) all.push_back(studies::allan_json(s));
      fmt::print("{}\n", nlohmann::ordered_json{{"channels", all}}.dump());
    }
    return 0;
  }
  for (std::size_t i = 0; i < studies.size(); ++i) fmt::print("{}{}", i ? "\n" : "", studies::allan_text(studies[i]));
  if (!o.plot.empty()) fmt::print("plot: {}\n", o.plot);
  return 0;
}

}  // namespace

void add_allan_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<AllanCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "allan", "Allan deviation with intervals and noise coefficients, before and after compensation");
  cmd->add_option("data", o->data, "Measurement CSV")->required();
  cmd->add_option("--fit", o->fit_file,
                  "Also the output compensated by this saved fit (as compensate --causal), side by side");
  cmd->add_option("--taus", o->taus, "τ set: octave (default: 1, 2, 4, … samples), decade, or all");
  cmd->add_option("--tau-max", o->tau_max,
                  "Longest τ in seconds (default a quarter of the record; it needs a gap-free stretch of 2τ)");
  cmd->add_option("--ci", o->ci, "Confidence of the intervals, between 0 and 1 (default 0.683, ±1σ)");
  cmd->add_option("--plot", o->plot, "Write the log-log figure (PNG) with bands and the coefficients read");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  add_data_options(cmd, o->data_options, false);
  cmd->callback([o, run] { *run = [o] { return run_allan(*o); }; });
}

}  // namespace gyrotherm::app
