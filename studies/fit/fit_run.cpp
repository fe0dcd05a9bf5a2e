#include "studies/fit/fit_run.h"

#include "fit/data/plausibility.h"

#include <fmt/format.h>

#include <filesystem>
#include <functional>

#include "fit/channels.h"
#include "fit/fit_file.h"
#include "fit/model/formula.h"
#include "sim/util/atomic_file.h"
#include "sim/util/format.h"
#include "sim/util/sha256.h"
#include "studies/record_source.h"

namespace gyrotherm::studies {
namespace {

std::string channel_text(const ChannelFit& c, const FitRun& run, bool units_said) {
  const std::vector<const fit::Term*>& terms = run.request.terms;
  const fit::PreparedData& data = c.data;
  const fit::ModelFit& result = c.result;
  std::string out = fmt::format("data: {}: {}{} every {:g} s, {} removed, {}, {}\n", data.file,
                                counted(data.raw_samples, "sample"), c.streamed ? " (streamed)" : "",
                                data.averaging.sample_interval_s, counted(data.outliers.removed, "glitch", "glitches"),
                                counted(data.averaging.gaps.size(), "gap"),
                                fit::describe_windows(data, c.pipeline));
  out += fit::units_text(data.units, data.cautions, !units_said);
  if (!data.outliers.times_s.empty()) {
    std::string times;
    for (std::size_t k = 0; k < data.outliers.times_s.size() && k < 8; ++k)
      times += fmt::format("{}{:g}", k ? ", " : "", data.outliers.times_s[k] - data.series.start_time_s);
    out += fmt::format("  glitches at {}{} s since the record's start\n", times,
                       data.outliers.times_s.size() > 8 ? ", ..." : "");
  }
  out += fmt::format("model: B = b0 + {}   engine: {}{}\n", fit::formula_text(terms), run.engine->name,
                     run.engine->stochastic ? fmt::format(" (seed {})", run.request.settings.seed) : "");
  std::map<std::string, double> errors;
  if (c.truth) errors = coefficient_errors(result, *c.truth);
  auto row = [&](const std::string& name, double value, const std::string& unit, std::size_t k) {
    std::string extra;
    const fit::TermInference& inference = result.engine.inference;
    if (k < inference.intervals.size())
      extra += fmt::format("  95% [{:.6g}, {:.6g}]", inference.intervals[k].lower, inference.intervals[k].upper);
    if (k < inference.kept.size() && !inference.kept[k])
      extra += "  (dropped by stepwise)";
    if (c.truth) {
      const auto it = c.truth->coefficients.find(name);
      if (it != c.truth->coefficients.end())
        extra += fmt::format("  truth {:.6g} ({:+.2f} %)", it->second, errors.count(name) ? 100.0 * errors[name] : 0.0);
      else
        extra += "  truth 0";
    }
    out += fmt::format("  {:<7} {:>13.6g} {:<14}{}\n", name, value, unit, extra);
  };
  const fit::SensorKind& kind = data.units.kind();
  row("1", result.coefficients.intercept, std::string(kind.unit), std::size_t(-1));
  for (std::size_t k = 0; k < terms.size(); ++k) {
    row(std::string(terms[k]->name), result.coefficients.b[k], terms[k]->coefficient_unit(kind.unit), k);
    if (!terms[k]->parameter) continue;
    std::string extra;
    if (const auto& i = result.parameter_intervals[k]) extra += fmt::format("  95% [{:.6g}, {:.6g}]", i->lower, i->upper);
    if (c.truth && c.truth->parameters.count(std::string(terms[k]->name)))
      extra += fmt::format("  truth {:.6g}", c.truth->parameters.at(std::string(terms[k]->name)));
    out += fmt::format("          {} = {:.6g}{}\n", terms[k]->parameter->name, result.parameters[k], extra);
  }
  if (result.engine.inference.interval_method.kind != fit::IntervalKind::none)
    out += fmt::format("  intervals: {}\n", fit::interval_method_text(result.engine.inference.interval_method,
                                                                      result.noise ? &result.noise->model : nullptr));
  out += fmt::format("record: {}\n", fit::describe_support(result.support));
  for (std::size_t k = 0; k < terms.size() && k < result.support.flags.size(); ++k)
    if (!result.support.flags[k].empty())
      out += fmt::format("  caution, {}: {}; its number is not a property of the {} alone\n",
                         terms[k]->name, result.support.flags[k], kind.noun);
  for (const fit::LagSensitivity& l : result.lag_sensitivity)
    if (l.lag_s < fit::kPlausibleSensorLagS)
      out += fmt::format("  caution, {}: a temperature sensor lagging the {} by {:.3g} s (which this record cannot "
                         "exclude) would move it by its 95 % half-width; give the sensor's time constant with "
                         "--sensor-tau if it is known\n",
                         terms[l.term]->name, kind.noun, l.lag_s);
  out += fmt::format("instability (std of {}): {:.6g} -> {:.6g} {} ({:.2f}x)\n", fit::averages_name(data, c.pipeline),
                     result.instability_before_dph, result.instability_after_dph, kind.unit, result.ratio());
  out += fmt::format("engine: {}\n", result.engine.brief_report());
  for (const std::string& w : fit::fit_warnings(result)) out += fmt::format("warning: {}\n", w);
  out += fmt::format("gap to the least-squares optimum: {:.3g} (relative)\n",
                     result.instability_after_dph / result.optimum_dph - 1.0);
  return out;
}

// Every channel of `source` fitted; truth(channel) the simulator's truth
// of a channel to set its fit against.
FitRun fit_record(const FitRequest& request, const RecordSource& source,
                  const std::function<std::optional<Truth>(const std::string&)>& truth) {
  FitRun run;
  run.request = request;
  run.request.data = source.name();
  run.engine = &fit::find_engine(request.engine);
  run.engine->make(request.settings);  // validates the options before any work
  const std::vector<const fit::Term*>& terms = request.terms;
  fit::PipelineOptions pipeline = fit::reading_columns_of(request.pipeline, terms);
  pipeline.columns = source.user_columns(pipeline.columns);
  const std::vector<std::string> channels = fit::parse_channels(pipeline.columns.gyro);
  run.channels =
      fit::for_each_channel(channels, pipeline, [&](const std::string& channel, const fit::PipelineOptions& p) {
        ChannelFit c;
        c.channel = channel;
        c.pipeline = p;
        // Large logs are read once, never held (fit/data/streaming.h); a table is never copied.
        c.data = source.prepare(c.pipeline, &c.streamed);
        fit::check_columns(terms, c.data, c.pipeline.columns);
        c.result = fit::with_cautions(c.data.cautions, [&] {
          try {
            return fit::fit_model(c.data, terms, *run.engine, request.settings);
          } catch (const FitError& e) {  // a record that cannot be fitted: which one
            throw FitError(fmt::format("{}{}: {}", c.data.file,
                                       channels.size() > 1 ? fmt::format(" ({})", channel) : std::string(), e.what()));
          }
        });
        // The simulator's truth of this channel (a gyro file without
        // channels: of its one gyro column).
        if (const std::optional<Truth> t = truth(channel); t && (channels.size() == 1 || t->channel_matched))
          c.truth = t;
        c.json = fit::fit_json(c.result, c.data, c.pipeline, request.settings);
        if (c.truth) add_truth(c.json, c.result, *c.truth);
        return c;
      });
  // An accelerometer's three axes together: their magnitude is gravity's, or a unit was misread.
  if (run.channels.size() == 3) {
    std::vector<std::vector<double>> axes;
    for (const ChannelFit& c : run.channels) axes.push_back(c.data.series.gyro_dph);
    run.gravity = fit::gravity_caution(run.channels.front().data.units, axes);
    if (run.gravity)
      for (ChannelFit& c : run.channels) c.json["data"]["cautions"].push_back(fit::caution_text(*run.gravity));
  }
  // The bytes fitted, hashed once for every channel (a table has no file).
  if (std::error_code ec; request.hash_data && !run.channels.empty() &&
                          std::filesystem::is_regular_file(run.channels.front().data.file, ec)) {
    const std::string sha256 = sha256_file_hex(run.channels.front().data.file);
    for (ChannelFit& c : run.channels) c.json["data"]["sha256"] = sha256;
  }
  if (run.channels.size() == 1) {
    run.json = run.channels.front().json.dump(2) + "\n";
  } else {
    std::vector<std::pair<std::string, nlohmann::ordered_json>> all;
    for (const ChannelFit& c : run.channels) all.emplace_back(c.channel, c.json);
    run.json = fit::channels_json(all).dump(2) + "\n";
  }
  if (!request.output.empty()) write_file_atomically(request.output, run.json);
  return run;
}

}  // namespace

FitRun run_fit(const FitRequest& request) {
  return fit_record(request, RecordSource(request.data),
                    [&](const std::string& channel) { return load_truth_beside(request.data, channel); });
}

FitRun run_fit(const FitRequest& request, const fit::Table& table, std::optional<Truth> truth) {
  return fit_record(request, RecordSource(table), [&](const std::string&) { return truth; });
}

std::string fit_text(const FitRun& run) {
  std::string out;
  const std::size_t n = run.channels.size();
  out += fit::shared_units_text(run.channels, [](const ChannelFit& c) -> const fit::Units& { return c.data.units; });
  const bool units_said = !out.empty();
  if (run.gravity) out += "caution (the three axes): " + fit::caution_text(*run.gravity) + "\n";
  for (const ChannelFit& c : run.channels) {
    if (n > 1) out += fmt::format("== channel {} ==\n", c.channel);
    out += channel_text(c, run, units_said);
  }
  if (n > 1) {
    out += fmt::format("\nsummary ({} channels, model B = b0 + {}):\n", n, fit::formula_text(run.request.terms));
    const std::string_view unit = run.channels.front().data.units.kind().unit;
    std::string header = fmt::format("  {:<14} {:>12} {:>12} {:>8}", "channel", fmt::format("before {}", unit),
                                     fmt::format("after {}", unit), "ratio");
    for (const fit::Term* t : run.request.terms) header += fmt::format(" {:>12}", t->name);
    out += header + "\n";
    for (const ChannelFit& c : run.channels) {
      std::string row = fmt::format("  {:<14} {:>12.6g} {:>12.6g} {:>8.2f}", c.channel, c.result.instability_before_dph,
                                    c.result.instability_after_dph, c.result.ratio());
      for (double b : c.result.coefficients.b) row += fmt::format(" {:>12.5g}", b);
      out += row + "\n";
    }
  }
  if (!run.request.output.empty()) out += fmt::format("wrote {}\n", run.request.output);
  return out;
}

}  // namespace gyrotherm::studies
