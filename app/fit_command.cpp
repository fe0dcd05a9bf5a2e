// gyrotherm fit DATA.csv [--model F] [--engine E] [--seed N] [--avg SECONDS]
//                        [--budget N] [--target SIGMA] [--option KEY=VALUE ...]
//                        [-o FIT.json] [--json]
// gyrotherm compensate DATA.csv --fit FIT.json [-o OUT.csv] [--causal] [--json]

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "app/commands.h"
#include "app/pipeline_options.h"
#include "fit/compensation.h"
#include "fit/fit_file.h"
#include "studies/simulated.h"
#include "fit/model/formula.h"
#include "fit/data/streaming.h"
#include "sim/util/atomic_file.h"
#include "sim/util/input_error.h"

namespace gyrotherm::app {
namespace {

struct FitOptions {
  std::string data;
  ModelOptions model;
  long budget = 0;
  double target = 0.0;
  std::vector<std::string> engine_options;
  std::string output;
  bool json = false;
  DataOptions data_options;
};

fit::EngineSettings engine_settings(const FitOptions& o) {
  fit::EngineSettings s;
  s.seed = o.model.seed;
  if (o.budget < 0) throw InputError(fmt::format("--budget {}: must be >= 0", o.budget));
  s.max_evaluations = o.budget;
  if (!(o.target >= 0.0) || !std::isfinite(o.target))
    throw InputError(fmt::format("--target {}: must be a finite sigma >= 0", o.target));
  s.target_objective = o.target;
  for (const std::string& kv : o.engine_options) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError(fmt::format("--option {}: expected KEY=VALUE (see 'gyrotherm engines')", kv));
    s.options[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  return s;
}

// One channel's fit, computed before anything is printed or written.
struct ChannelFit {
  std::string channel;
  fit::PipelineOptions pipeline;
  fit::PreparedData data;
  fit::ModelFit result;
  std::optional<studies::Truth> truth;
  bool streamed = false;
  nlohmann::ordered_json json;
};

void print_fit(const ChannelFit& c, const std::vector<const fit::Term*>& terms,
               const fit::EngineInfo& engine, const fit::EngineSettings& settings) {
  const fit::PreparedData& data = c.data;
  const fit::ModelFit& result = c.result;
  const std::optional<studies::Truth>& truth = c.truth;
  fmt::print("data: {}: {} samples{} every {:g} s, {} glitches removed, {} gaps, {}\n", data.file,
             data.raw_samples, c.streamed ? " (streamed)" : "", data.averaging.sample_interval_s,
             data.outliers.removed, data.averaging.gaps.size(), fit::describe_windows(data, c.pipeline));
  if (!c.pipeline.columns.units.identity())
    fmt::print("  units converted: {}\n", c.pipeline.columns.units.description());
  if (!data.outliers.times_s.empty()) {
    std::string times;
    for (std::size_t k = 0; k < data.outliers.times_s.size() && k < 8; ++k)
      times += fmt::format("{}{:g}", k ? ", " : "", data.outliers.times_s[k]);
    fmt::print("  glitches at t = {}{} s\n", times, data.outliers.times_s.size() > 8 ? ", ..." : "");
  }
  fmt::print("model: B = b0 + {}   engine: {}{}\n", fit::formula_text(terms), engine.name,
             engine.stochastic ? fmt::format(" (seed {})", settings.seed) : "");
  std::map<std::string, double> errors;
  if (truth) errors = studies::coefficient_errors(result, *truth);
  auto print_row = [&](const std::string& name, double value, const std::string& unit, std::size_t k) {
    std::string extra;
    if (k < result.engine.intervals.size())
      extra += fmt::format("  95% [{:.6g}, {:.6g}]", result.engine.intervals[k].lower,
                           result.engine.intervals[k].upper);
    if (!result.engine.kept.empty() && k < result.engine.kept.size() && !result.engine.kept[k])
      extra += "  (dropped by stepwise)";
    if (truth) {
      const auto it = truth->coefficients.find(name);
      if (it != truth->coefficients.end())
        extra += fmt::format("  truth {:.6g} ({:+.2f} %)", it->second,
                             errors.count(name) ? 100.0 * errors[name] : 0.0);
      else
        extra += "  truth 0";
    }
    fmt::print("  {:<7} {:>13.6g} {:<14}{}\n", name, value, unit, extra);
  };
  print_row("1", result.coefficients.intercept, "°/h", std::size_t(-1));
  for (std::size_t k = 0; k < terms.size(); ++k) {
    print_row(std::string(terms[k]->name), result.coefficients.b[k], terms[k]->coefficient_unit(), k);
    if (terms[k]->parameter) {
      std::string extra;
      if (const auto& i = result.parameter_intervals[k])
        extra += fmt::format("  95% [{:.6g}, {:.6g}]", i->lower, i->upper);
      if (truth && truth->parameters.count(std::string(terms[k]->name)))
        extra += fmt::format("  truth {:.6g}", truth->parameters.at(std::string(terms[k]->name)));
      fmt::print("          {} = {:.6g}{}\n", terms[k]->parameter->name, result.parameters[k], extra);
    }
  }
  if (!result.engine.interval_method.empty())
    fmt::print("  intervals: {}\n", result.engine.interval_method);
  fmt::print("instability (std of {}): {:.6g} -> {:.6g} °/h ({:.2f}x)\n",
             fit::averages_name(data, c.pipeline), result.instability_before_dph,
             result.instability_after_dph, result.ratio());
  fmt::print("engine: {}\n", result.engine.brief_report());
  for (const std::string& w : result.warnings) fmt::print("warning: {}\n", w);
  fmt::print("gap to the least-squares optimum: {:.3g} (relative)\n",
             result.instability_after_dph / result.optimum_dph - 1.0);
}

int run_fit(const FitOptions& o) {
  const std::vector<const fit::Term*> terms = o.model.terms();
  const fit::EngineInfo& engine = fit::find_engine(o.model.engine);
  const fit::EngineSettings settings = engine_settings(o);
  engine.make(settings);  // validates the options before any work
  const fit::PipelineOptions pipeline = fit::reading_columns_of(o.data_options.resolved(), terms);
  const std::vector<std::string> channels = o.data_options.channels();
  // Every channel is fitted before anything is written: a bad one leaves no file.
  const std::vector<ChannelFit> fits =
      for_each_channel(channels, pipeline, [&](const std::string& channel, const fit::PipelineOptions& p) {
        ChannelFit c;
        c.channel = channel;
        c.pipeline = p;
        // Large logs are read twice, never held (fit/data/streaming.h).
        c.data = fit::prepare_csv(o.data, c.pipeline, &c.streamed);
        fit::check_columns(terms, c.data, c.pipeline.columns);
        c.result = fit::fit_model(c.data, terms, engine, settings);
        // The simulator's truth belongs to its one gyro column.
        if (channels.size() == 1) c.truth = studies::load_truth_beside(o.data);
        c.json = fit::fit_json(c.result, c.data, c.pipeline, settings);
        if (c.truth) studies::add_truth(c.json, c.result, *c.truth);
        return c;
      });
  std::string json;
  if (fits.size() == 1) {
    json = fits.front().json.dump(2) + "\n";
  } else {
    std::vector<std::pair<std::string, nlohmann::ordered_json>> all;
    for (const ChannelFit& c : fits) all.emplace_back(c.channel, c.json);
    json = fit::channels_json(all).dump(2) + "\n";
  }
  if (!o.output.empty()) write_file_atomically(o.output, json);
  if (o.json) {
    fmt::print("{}", json);
    return 0;
  }
  for (const ChannelFit& c : fits) {
    if (fits.size() > 1) fmt::print("== channel {} ==\n", c.channel);
    print_fit(c, terms, engine, settings);
  }
  if (fits.size() > 1) {
    fmt::print("\nsummary ({} channels, model B = b0 + {}):\n", fits.size(), fit::formula_text(terms));
    std::string header = fmt::format("  {:<14} {:>12} {:>12} {:>8}", "channel", "before °/h", "after °/h", "ratio");
    for (const fit::Term* t : terms) header += fmt::format(" {:>12}", t->name);
    fmt::print("{}\n", header);
    for (const ChannelFit& c : fits) {
      std::string row = fmt::format("  {:<14} {:>12.6g} {:>12.6g} {:>8.2f}", c.channel,
                                    c.result.instability_before_dph, c.result.instability_after_dph,
                                    c.result.ratio());
      for (double b : c.result.coefficients.b) row += fmt::format(" {:>12.5g}", b);
      fmt::print("{}\n", row);
    }
  }
  if (!o.output.empty()) fmt::print("wrote {}\n", o.output);
  return 0;
}

struct CompensateOptions {
  std::string data;
  std::string fit_file;
  std::string output;
  bool causal = false;
  bool json = false;
};

int run_compensate(const CompensateOptions& o) {
  const std::vector<fit::SavedFit> saved = fit::load_fits(o.fit_file);
  // Every channel the fit holds, each with its own columns and units, all
  // computed before anything is written.
  std::vector<std::pair<std::string, fit::Compensation>> done;
  std::vector<std::pair<std::string, nlohmann::ordered_json>> json;
  bool streamed = false;
  for (const fit::SavedFit& fit : saved) {
    fit::PipelineOptions pipeline = fit::reading_columns_of(fit.pipeline, fit.terms);
    if (o.causal) pipeline.derivative = fit::DerivativeMode::causal;
    try {
      // A log too large to hold, one channel: never held, the output written
      // as it is computed (fit/compensation.h).
      streamed = saved.size() == 1 && fit::streams(o.data, pipeline);
      if (streamed) {
        done.emplace_back(fit.channel, fit::compensate_streaming(o.data, fit, pipeline, o.output));
      } else {
        const fit::Measurement m = fit::read_measurement_csv(o.data, pipeline.columns);
        done.emplace_back(fit.channel, fit::compensate(m, fit, pipeline));
      }
    } catch (const InputError& e) {
      if (saved.size() == 1) throw;
      throw InputError(fmt::format("channel {}: {}", fit.channel, e.what()));
    }
    json.emplace_back(fit.channel, fit::compensation_json(done.back().second, fit, pipeline, o.data,
                                                          o.fit_file, o.output));
  }
  if (!o.output.empty() && !streamed) {
    if (done.size() == 1)
      fit::write_compensated_csv(o.output, done.front().second);
    else
      fit::write_compensated_csv(o.output, done);
  }
  if (o.json) {
    fmt::print("{}\n", saved.size() == 1 ? json.front().second.dump() : fit::channels_json(json).dump());
    return 0;
  }
  for (std::size_t i = 0; i < saved.size(); ++i) {
    const fit::SavedFit& fit = saved[i];
    const fit::Compensation& c = done[i].second;
    fmt::print("compensate {}{} with {} ({}: B = b0 + {}, {} derivatives)\n", o.data,
               saved.size() > 1 ? ", channel " + fit.channel : "", o.fit_file, fit.engine,
               fit::formula_text(fit.terms), json[i].second["derivative"].get<std::string>());
    fmt::print("instability (std of {}): {:.6g} -> {:.6g} °/h ({:.2f}x)\n",
               fit::averages_name(c.data, fit.pipeline), c.before_dph, c.after_dph, c.ratio());
  }
  if (!o.output.empty()) fmt::print("wrote {}\n", o.output);
  return 0;
}

}  // namespace

void add_fit_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<FitOptions>();
  CLI::App* cmd = app.add_subcommand("fit", "Fit a bias model to measurements (CSV)");
  cmd->add_option("data", o->data, "Measurement CSV (time_s, temp_c, gyro_dph[, temp2_c])")->required();
  add_model_options(cmd, o->model, "Add a term to the model (repeatable)");
  cmd->add_option("--budget", o->budget, "Maximum objective evaluations (0: the engine's default)");
  cmd->add_option("--target", o->target, "Stop when sigma <= this, °/h (0: none)");
  cmd->add_option("--option", o->engine_options, "Engine option KEY=VALUE (repeatable)");
  cmd->add_option("-o,--output", o->output, "Save the fit as JSON (for compensate)");
  cmd->add_flag("--json", o->json, "Print the fit as one JSON object");
  add_data_options(cmd, o->data_options);
  cmd->callback([o, run] { *run = [o] { return run_fit(*o); }; });
}

void add_compensate_command(CLI::App& app, Run* run) {
  auto o = std::make_shared<CompensateOptions>();
  CLI::App* cmd = app.add_subcommand("compensate", "Apply a saved fit to other data");
  cmd->add_option("data", o->data, "Measurement CSV")->required();
  cmd->add_option("--fit", o->fit_file, "Fit saved by 'gyrotherm fit -o'")->required();
  cmd->add_option("-o,--output", o->output,
                  "Write time_s, temp_c, gyro_dph, model_dph, compensated_dph, outlier");
  cmd->add_flag("--causal", o->causal,
                "Real-time compensation: backward differences and only past windows");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->callback([o, run] { *run = [o] { return run_compensate(*o); }; });
}

}  // namespace gyrotherm::app
