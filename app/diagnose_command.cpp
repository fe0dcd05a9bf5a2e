// gyrotherm diagnose DATA.csv [--model F] [--add TERM ...] [--engine E]
//                            [--plots DIR] [--json]
// The five steps of studies/diagnose/diagnosis.h: compare with the noise floor, where the
// model fails, which effect is missing, add it, watch the error fall.

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim/util/comma_list.h"
#include "app/commands.h"
#include "fit/data/streaming.h"
#include "studies/diagnose/diagnose_plots.h"
#include "app/pipeline_options.h"
#include "fit/fit_file.h"
#include "studies/diagnose/report.h"
#include "fit/model/formula.h"
#include "sim/util/format.h"
#include "sim/util/input_error.h"

namespace gyrotherm::app {
namespace {

struct DiagnoseOptions {
  std::string data;
  ModelOptions model;
  std::string candidates;
  std::string plots;
  bool json = false;
  DataOptions data_options;
};

std::string hours(double s) { return fmt::format("{:.2f} h", s / 3600.0); }

// One channel's diagnosis, computed before anything is printed or written.
struct ChannelDiagnosis {
  std::string channel;
  fit::PipelineOptions pipeline;
  fit::Measurement measurement;
  fit::PreparedData data;
  studies::DiagnoseReport report;
  bool streamed = false;  // prepared in one pass: no samples held, no log columns as candidates
};

void print_diagnosis(const DiagnoseOptions& o, const ChannelDiagnosis& channel,
                     const std::vector<const fit::Term*>& terms, const fit::EngineInfo& engine,
                     const std::string& plots) {
  const fit::PipelineOptions& pipeline = channel.pipeline;
  const fit::PreparedData& data = channel.data;
  const studies::Diagnosis& d = channel.report.diagnosis;
  const std::optional<studies::Diagnosis>& before = channel.report.before;
  const std::string& next = channel.report.next_command;
  fmt::print("diagnose {}: model B = b0 + {} ({}), {}, {} glitches removed\n",
             o.data, fit::formula_text(terms), engine.name, fit::describe_windows(data, pipeline),
             data.outliers.removed);
  if (channel.streamed)
    fmt::print("   (over {} MB: read in one pass without holding the samples; the log's other columns are "
               "not tried as candidates{})\n",
               fit::streaming_threshold_bytes() >> 20, plots.empty() ? "" : ", and the full-rate Allan figure is left out");
  fmt::print("1. compare: instability {} -> {} °/h; noise floor {} °/h ({}):\n"
             "   the model is {:.2f} times the floor\n",
             human(d.fit.instability_before_dph), human(d.fit.instability_after_dph),
             human(d.noise_floor_dph), d.floor.description(), d.excess_ratio());
  if (d.floor.method == "hadamard" && d.floor.within_dph > 0.0 && d.floor.within_dph < 0.7 * d.floor.dph)
    fmt::print("   (the scatter inside the windows alone gives {} °/h: the rest of the floor is noise "
               "slower than a window, bias instability)\n",
               human(d.floor.within_dph));
  fmt::print("2. where it fails (residual RMS over the floor, worst first):\n");
  const auto worst = d.worst_segments();
  for (std::size_t k = 0; k < worst.size() && k < 6; ++k) {
    const studies::SegmentReport& s = d.segments[worst[k]];
    fmt::print("   {:<8} {:>8} – {:<8} {:6.1f} .. {:5.1f} °C  {:5.2f}x\n", s.kind, hours(s.start_s),
               hours(s.end_s), s.temp_min_c, s.temp_max_c, s.ratio_to_floor);
  }
  std::string bands;
  for (const auto& b : d.bands)
    bands += fmt::format("{}{:.0f}..{:.0f} °C {:.2f}x", bands.empty() ? "" : ", ", b.temp_min_c,
                         b.temp_max_c, b.ratio_to_floor);
  fmt::print("   by temperature: {}\n", bands);
  fmt::print("3. missing effects (share of the excess removed; block cross-validation p):\n");
  for (std::size_t k = 0; k < d.candidates.size(); ++k) {
    const studies::CandidateReport& c = d.candidates[k];
    fmt::print("   {} {:<12} {:5.0f} %  p = {:<8.2g} {:<12} {}\n", c.significant ? "*" : " ",
               c.term->name, c.reduction_pct, c.p_value, c.significant ? "significant" : "",
               c.term->meaning);
  }
  if (!d.skipped.empty()) {
    std::string skipped;
    for (const auto& s : d.skipped) skipped += (skipped.empty() ? "" : "; ") + s;
    fmt::print("   not tried: {}\n", skipped);
  }
  if (before) {
    fmt::print("5. before/after adding {}: {:.5f} -> {:.5f} °/h (floor {:.5f})\n",
               fmt::join(o.model.add, ", "), before->fit.instability_after_dph,
               d.fit.instability_after_dph, d.noise_floor_dph);
    const auto rows = studies::segment_rms(*before, before->residual_dph);
    for (std::size_t i = 0; i < rows.size() && i < d.segments.size(); ++i)
      fmt::print("   {:<8} {:>8} – {:<8} {:5.2f}x -> {:5.2f}x\n", rows[i].kind, hours(rows[i].start_s),
                 hours(rows[i].end_s), rows[i].ratio_to_floor, d.segments[i].ratio_to_floor);
  }
  for (const std::string& w : d.fit.warnings) fmt::print("warning: {}\n", w);
  for (const studies::StepEvent& e : d.events)
    fmt::print("event: a bias step at {} of {:+.3g} °/h (95 % [{:.3g}, {:.3g}]){}\n", hours(e.time_s),
               e.size_dph, e.size_interval_dph.lower, e.size_interval_dph.upper,
               e.significant ? ", significant" : ", not significant against the other candidates");
  for (const std::string& n : d.confounding_notes) fmt::print("cannot tell: {}\n", n);
  fmt::print("verdict: {}\n", d.verdict);
  if (!next.empty()) fmt::print("next: {}\n", next);
  if (!plots.empty()) fmt::print("plots in {}/\n", plots);
}


int run_diagnose(const DiagnoseOptions& o) {
  const std::vector<const fit::Term*> base_terms = o.model.base_terms();
  const std::vector<const fit::Term*> terms = o.model.terms();
  const fit::EngineInfo& engine = fit::find_engine(o.model.engine);
  fit::EngineSettings settings;
  settings.seed = o.model.seed;
  engine.make(settings);  // validates the settings before any work
  const fit::PipelineOptions pipeline = o.data_options.resolved();
  const std::vector<std::string> channels = o.data_options.channels();
  studies::DiagnosisOptions diagnosis_options;
  diagnosis_options.candidates = split_commas(o.candidates);
  diagnosis_options.excluded_columns = channels;  // no gyro channel explains another
  const fit::PipelineOptions with_columns = fit::reading_columns_of(pipeline, terms);
  std::vector<ChannelDiagnosis> all =
      for_each_channel(channels, with_columns, [&](const std::string& channel, const fit::PipelineOptions& p) {
        ChannelDiagnosis c;
        c.channel = channel;
        c.pipeline = p;
        // A log too large to hold is prepared in one pass (fit/data/streaming.h),
        // without its other columns; otherwise every other numeric column of the
        // log may be a candidate.
        c.streamed = fit::streams(o.data, c.pipeline);
        if (c.streamed) {
          c.data = fit::prepare_data_streaming(o.data, c.pipeline);
        } else {
          c.pipeline.columns.other_numeric = true;
          c.measurement = fit::read_measurement_csv(o.data, c.pipeline.columns);
          c.data = fit::prepare_data(c.measurement, c.pipeline);
        }
        c.report = studies::diagnose_record(c.data, c.pipeline.columns, base_terms, terms, engine, settings,
                                        diagnosis_options);
        if (channels.size() > 1 && !c.report.next_command.empty())
          c.report.next_command += " --gyro-col " + channel;
        return c;
      });
  // With several channels, each one's figures in a folder of its own.
  std::vector<std::string> plots(all.size(), o.plots);
  for (std::size_t i = 0; i < all.size() && !o.plots.empty(); ++i) {
    if (all.size() > 1) plots[i] = (std::filesystem::path(o.plots) / all[i].channel).string();
    const studies::Diagnosis& d = all[i].report.diagnosis;
    const std::optional<studies::Diagnosis>& before = all[i].report.before;
    studies::write_diagnosis_plots(plots[i], all[i].measurement, all[i].data, d,
                               before ? &*before : nullptr);
  }
  if (o.json) {
    if (all.size() == 1) {
      fmt::print("{}\n", studies::diagnosis_json(all.front().report).dump());
    } else {
      std::vector<std::pair<std::string, nlohmann::ordered_json>> list;
      for (const ChannelDiagnosis& c : all) list.emplace_back(c.channel, studies::diagnosis_json(c.report));
      fmt::print("{}\n", fit::channels_json(list).dump());
    }
    return 0;
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all.size() > 1) fmt::print("{}== channel {} ==\n", i ? "\n" : "", all[i].channel);
    print_diagnosis(o, all[i], terms, engine, plots[i]);
  }
  if (all.size() > 1) {
    fmt::print("\nsummary ({} channels, model B = b0 + {}):\n", all.size(), fit::formula_text(terms));
    fmt::print("  {:<14} {:>12} {:>12} {:>8}  {}\n", "channel", "after °/h", "floor °/h", "x floor",
               "best candidate");
    for (const ChannelDiagnosis& c : all) {
      const studies::Diagnosis& d = c.report.diagnosis;
      std::string best = "none";
      if (!d.candidates.empty()) {
        const studies::CandidateReport& b = d.candidates.front();
        best = fmt::format("{} ({:.0f} %{})", b.term->name, b.reduction_pct,
                           b.significant ? (b.confounded_with.empty() ? ", significant" : ", significant, not alone")
                                         : "");
      }
      fmt::print("  {:<14} {:>12.5g} {:>12.5g} {:>8.2f}  {}\n", c.channel, d.fit.instability_after_dph,
                 d.noise_floor_dph, d.excess_ratio(), best);
    }
  }
  return 0;
}

}  // namespace

void add_diagnose_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<DiagnoseOptions>();
  CLI::App* cmd = app.add_subcommand(
      "diagnose", "Where a bias model fails on measurements, and which physical effect is missing");
  cmd->add_option("data", o->data, "Measurement CSV")->required();
  add_model_options(cmd, o->model, "Add a term and compare before/after (repeatable)");
  cmd->add_option("--candidates", o->candidates,
                  "Candidates to try: a comma list (terms, columns, 'step'), or +NAME/-NAME to add to or "
                  "remove from the default set (every other term, every numeric column, the steps found)");
  cmd->add_option("--plots", o->plots, "Write PNG figures into this folder");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  add_data_options(cmd, o->data_options);
  cmd->callback([o, run] { *run = [o] { return run_diagnose(*o); }; });
}

}  // namespace gyrotherm::app
