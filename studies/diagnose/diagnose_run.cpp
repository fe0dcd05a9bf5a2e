#include "studies/diagnose/diagnose_run.h"

#include "fit/data/plausibility.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "fit/channels.h"
#include "fit/data/streaming.h"
#include "fit/fit_file.h"
#include "fit/model/formula.h"
#include "sim/util/format.h"
#include "studies/diagnose/diagnose_plots.h"
#include "studies/options/pipeline_options.h"
#include "studies/record_source.h"

namespace gyrotherm::studies {
namespace {

std::string channel_text(const DiagnoseRun& run, const ChannelDiagnosis& channel, bool units_said) {
  const fit::PipelineOptions& pipeline = channel.pipeline;
  const fit::PreparedData& data = channel.data;
  const Diagnosis& d = channel.report.diagnosis;
  const std::optional<Diagnosis>& before = channel.report.before;
  std::string out = fmt::format("diagnose {}: model B = b0 + {} ({}), {}, {} removed\n", run.request.data,
                                fit::formula_text(run.request.terms), run.request.engine,
                                fit::describe_windows(data, pipeline), counted(data.outliers.removed, "glitch", "glitches"));
  out += fit::units_text(data.units, data.cautions, !units_said);
  if (channel.streamed)
    out += fmt::format(
        "   (over {} MB: read in one pass without holding the samples; the log's other columns are not tried as "
        "candidates{})\n",
        fit::streaming_threshold_bytes() >> 20, channel.plots.empty() ? "" : ", and the full-rate Allan figure is left out");
  const std::string_view unit = d.sensor->unit;
  out += fmt::format("1. compare: instability {} -> {} {}; noise floor {} {} ({}):\n"
                     "   the model is {:.2f} times the floor\n",
                     human(d.fit.instability_before_dph), human(d.fit.instability_after_dph), unit,
                     human(d.noise_floor_dph), unit, floor_description(d.floor), d.excess_ratio());
  if (d.floor.method == FloorMethod::hadamard && d.floor.within_dph > 0.0 && d.floor.within_dph < 0.7 * d.floor.dph)
    out += fmt::format("   (the scatter inside the windows alone gives {} {}: the rest of the floor is noise "
                       "slower than a window, bias instability)\n",
                       human(d.floor.within_dph), unit);
  out += "2. where it fails (residual RMS over the floor, worst first; hours since the record's start):\n";
  // Temperatures with the decimals that tell every segment's (every band's)
  // ends apart: a record spanning a few degrees has bands narrower than 1 °C.
  const auto worst = d.worst_segments();
  const std::size_t shown = std::min<std::size_t>(worst.size(), 6);
  int decimals = 1;
  for (std::size_t k = 0; k < shown; ++k)
    decimals = std::max(decimals, decimals_to_tell_apart(d.segments[worst[k]].temp_min_c,
                                                         d.segments[worst[k]].temp_max_c, 1));
  for (std::size_t k = 0; k < shown; ++k) {
    const SegmentReport& s = d.segments[worst[k]];
    out += fmt::format("   {:<8} {:>8} – {:<8} {:6.{}f} .. {:5.{}f} °C  {:5.2f}x\n", to_string(s.kind),
                       hours_text(s.start_s), hours_text(s.end_s), s.temp_min_c, decimals, s.temp_max_c, decimals,
                       s.ratio_to_floor);
  }
  decimals = 0;
  for (const auto& b : d.bands) decimals = std::max(decimals, decimals_to_tell_apart(b.temp_min_c, b.temp_max_c, 0));
  std::string bands;
  for (const auto& b : d.bands)
    bands += fmt::format("{}{:.{}f}..{:.{}f} °C {:.2f}x", bands.empty() ? "" : ", ", b.temp_min_c, decimals,
                         b.temp_max_c, decimals, b.ratio_to_floor);
  out += fmt::format("   by temperature: {}\n", bands);
  out += "3. missing effects (share of the excess removed; p under the record's noise, and the level it must reach; "
         "meaning (coefficient as added)):\n";
  for (const CandidateReport& c : d.candidates)
    out += fmt::format("   {} {:<12} {:>7}  p = {:<8} (< {:<7.2g}) {:<12} {} ({:.3g} {})\n", c.passed() ? "*" : " ",
                       c.term->name, share_cell(c.reduction_pct), p_text(c.p_value, c.level), c.level,
                       !c.passed() ? "" : c.confounded_with.empty() ? "significant" : "its group is",
                       c.term->meaning, c.coefficient, c.term->coefficient_unit(unit));
  if (!d.columns_tried.empty())
    out += fmt::format("   the log's columns tried as causes (each with its rate): {}\n", fmt::join(d.columns_tried, ", "));
  if (!d.skipped.empty()) out += fmt::format("   not tried: {}\n", fmt::join(skipped_texts(d.skipped), "; "));
  if (d.noise && d.fit.noise && d.noise->model.description() != d.fit.noise->model.description())
    out += fmt::format("   the record's noise with the effects found as fixed effects: {}\n",
                       d.noise->model.description());
  if (before) {
    out += fmt::format("5. before/after adding {}: {:.5f} -> {:.5f} {} (floor {:.5f})\n",
                       fmt::join(run.request.added, ", "), before->fit.instability_after_dph,
                       d.fit.instability_after_dph, unit, d.noise_floor_dph);
    const auto rows = segment_rms(*before, before->residual_dph());
    for (std::size_t i = 0; i < rows.size() && i < d.segments.size(); ++i)
      out += fmt::format("   {:<8} {:>8} – {:<8} {:5.2f}x -> {:5.2f}x\n", to_string(rows[i].kind),
                         hours_text(rows[i].start_s), hours_text(rows[i].end_s), rows[i].ratio_to_floor,
                         d.segments[i].ratio_to_floor);
  }
  for (const std::string& w : fit::fit_warnings(d.fit)) out += fmt::format("warning: {}\n", w);
  for (const StepEvent& e : d.events)
    out += fmt::format("event: a bias step at {} of {:+.3g} {} (95 % [{:.3g}, {:.3g}]){}\n", hours_text(e.time_s),
                       e.size_dph, unit, e.size_interval_dph.lower, e.size_interval_dph.upper,
                       e.significant ? ", significant" : ", not significant against the other candidates");
  for (const ConfoundingGroup& g : d.confounded) out += fmt::format("cannot tell: {}\n", confounding_text(g));
  out += fmt::format("verdict: {}\n", verdict_text(d));
  if (const std::string next = next_command(channel.report); !next.empty()) out += fmt::format("next: {}\n", next);
  if (const auto& plan = channel.report.plan)
    out += fmt::format("next: to design a test that separates them: {}\n"
                       "      (add --noise FILE, this diagnose's --json saved to FILE, for the record's own noise; {})\n",
                       plan_command_text(*plan),
                       plan->range_too_narrow
                           ? fmt::format("add --range LO,HI, your chamber's, wider than the record's {:g}..{:g} °C, "
                                         "over which they cannot be separated; without it plan takes its scenario's "
                                         "set points",
                                         plan->low_c, plan->high_c)
                           : fmt::format("--range is the record's temperatures rounded outward to {:g} °C: give "
                                         "your chamber's",
                                         kPlanRangeStepC));
  if (!channel.plots.empty()) out += fmt::format("plots in {}/\n", channel.plots);
  return out;
}

DiagnoseRun diagnose_record(const DiagnoseRequest& request, const RecordSource& source) {
  DiagnoseRun run;
  run.request = request;
  run.request.data = source.name();
  run.request.pipeline.columns = source.user_columns(request.pipeline.columns);
  const fit::EngineInfo& engine = fit::find_engine(request.engine);
  engine.make(request.settings);  // validates the settings before any work
  const std::vector<std::string> channels = fit::parse_channels(run.request.pipeline.columns.gyro);
  DiagnosisOptions options = request.options;
  options.excluded_columns = channels;  // no gyro channel explains another
  // Progress only where the work is long: a large log, or one streamed.
  const bool large = source.bytes() > request.progress_above_bytes;
  bool show = false;
  std::size_t channel_index = 0;
  const auto report = [&](const std::string& what, double within) {
    if (show)
      request.progress(what, (static_cast<double>(channel_index) + within) / static_cast<double>(channels.size()));
  };
  const fit::PipelineOptions with_columns = fit::reading_columns_of(run.request.pipeline, request.terms);
  run.channels =
      fit::for_each_channel(channels, with_columns, [&](const std::string& channel, const fit::PipelineOptions& p) {
        ChannelDiagnosis c;
        c.channel = channel;
        c.pipeline = p;
        c.streamed = source.streams(c.pipeline);
        show = request.progress && (large || c.streamed);
        report(fmt::format("{}: reading {}", channel, source.name()), 0.0);
        if (c.streamed) {
          c.data = fit::prepare_data_streaming(source.name(), c.pipeline);
        } else {
          c.pipeline.columns.other_numeric = true;
          c.measurement = source.read(c.pipeline.columns);
          c.data = fit::prepare_data(c.measurement, c.pipeline);
        }
        DiagnosisOptions with_stages = options;
        double within = 0.3;
        with_stages.stage = [&](const std::string& stage) {
          report(fmt::format("{}: {}", channel, stage), within);
          within = std::min(0.95, within + 0.1);
        };
        report(fmt::format("{}: {} windows read", channel, c.data.series.size()), 0.25);
        c.report = fit::with_cautions(c.data.cautions, [&] {
          return diagnose_record(c.data, c.pipeline.columns, request.base_terms, request.terms, engine,
                                 request.settings, with_stages);
        });
        ++channel_index;
        report(fmt::format("{}: done", channel), 0.0);
        if (channels.size() > 1) c.report.channel = channel;
        c.report.data_options = given_data_options(request.pipeline);
        if (source.table() != nullptr) c.report.style = CallStyle::python;
        return c;
      });
  // With several channels, each one's figures in a folder of its own, named
  // after it (made safe for a file name: "gyrox rad/s" would nest folders).
  const std::vector<std::string> folders = fit::channel_file_names(channels);
  for (std::size_t i = 0; i < run.channels.size(); ++i) {
    ChannelDiagnosis& c = run.channels[i];
    if (request.plots.empty()) continue;
    c.plots = run.channels.size() > 1 ? (std::filesystem::path(request.plots) / folders[i]).string() : request.plots;
    write_diagnosis_plots(c.plots, c.measurement, c.data, c.report.diagnosis,
                          c.report.before ? &*c.report.before : nullptr);
  }
  return run;
}

}  // namespace

DiagnoseRun run_diagnose(const DiagnoseRequest& request) { return diagnose_record(request, RecordSource(request.data)); }

DiagnoseRun run_diagnose(const DiagnoseRequest& request, const fit::Table& table) {
  return diagnose_record(request, RecordSource(table));
}

nlohmann::ordered_json diagnose_json(const DiagnoseRun& run) {
  // The report and, as fit's data.units and data.cautions, how the record was read.
  const auto one = [](const ChannelDiagnosis& c) {
    nlohmann::ordered_json j = diagnosis_json(c.report);
    j["units"] = c.data.units.used();
    j["cautions"] = fit::caution_texts(c.data.cautions);
    return j;
  };
  if (run.channels.size() == 1) return one(run.channels.front());
  std::vector<std::pair<std::string, nlohmann::ordered_json>> list;
  for (const ChannelDiagnosis& c : run.channels) list.emplace_back(c.channel, one(c));
  return fit::channels_json(list);
}

std::string diagnose_text(const DiagnoseRun& run) {
  std::string out;
  const std::size_t n = run.channels.size();
  out += fit::shared_units_text(run.channels,
                                [](const ChannelDiagnosis& c) -> const fit::Units& { return c.data.units; });
  const bool units_said = !out.empty();
  for (std::size_t i = 0; i < n; ++i) {
    if (n > 1) out += fmt::format("{}== channel {} ==\n", i ? "\n" : "", run.channels[i].channel);
    out += channel_text(run, run.channels[i], units_said);
  }
  if (n < 2) return out;
  out += fmt::format("\nsummary ({} channels, model B = b0 + {}):\n", n, fit::formula_text(run.request.terms));
  const std::string_view unit = run.channels.front().report.diagnosis.sensor->unit;
  out += fmt::format("  {:<14} {:>12} {:>12} {:>8}  {}\n", "channel", fmt::format("after {}", unit),
                     fmt::format("floor {}", unit), "x floor", "missing effect");
  for (const ChannelDiagnosis& c : run.channels) {
    const Diagnosis& d = c.report.diagnosis;
    // The top candidate, named as the answer only when it passed the test.
    std::string best = "nothing left to try";
    if (!d.candidates.empty()) {
      const CandidateReport& b = d.candidates.front();
      best = !b.passed() ? fmt::format("none significant (top: {} removes {}, p = {:.2g})", b.term->name,
                                       share_cell(b.reduction_pct), b.p_value)
                         : fmt::format("{}: {}, {}", b.term->name, share_cell(b.reduction_pct),
                                       b.confounded_with.empty() ? "significant" : "its group significant");
    }
    out += fmt::format("  {:<14} {:>12.5g} {:>12.5g} {:>8.2f}  {}\n", c.channel, d.fit.instability_after_dph,
                       d.noise_floor_dph, d.excess_ratio(), best);
  }
  return out;
}

}  // namespace gyrotherm::studies
