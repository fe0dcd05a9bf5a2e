#include "app/pipeline_options.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "sim/util/input_error.h"

namespace gyrotherm::app {

fit::PipelineOptions DataOptions::resolved() const {
  fit::PipelineOptions p = pipeline;
  p.columns.units.validate();
  if (keep_outliers && outlier_threshold)
    throw InputError("--keep-outliers and --outlier-threshold contradict each other: keep the "
                     "glitches, or set the rule that removes them, not both");
  if (outlier_threshold) {
    if (!(*outlier_threshold > 0.0))
      throw InputError(fmt::format("--outlier-threshold {}: must be > 0 (robust sigmas)", *outlier_threshold));
    p.outliers.threshold = *outlier_threshold;
  }
  if (!(p.derivative_span_s > 0.0) || !std::isfinite(p.derivative_span_s))
    throw InputError(fmt::format("--deriv-span {}: must be a number of seconds > 0", p.derivative_span_s));
  if (causal) p.derivative = fit::DerivativeMode::causal;
  if (keep_outliers) p.remove_outliers = false;
  return p;
}

void add_column_options(CLI::App* cmd, fit::ColumnMap& c, bool fit_defaults) {
  const auto is = [&](const std::string& plain) { return fit_defaults ? std::string(" (default: the fit's)") : plain; };
  cmd->add_option("--time-col", c.time, "Name of the time column" + is(" (default time_s)"));
  cmd->add_option("--temp-col", c.temp, "Name of the gyro temperature column" + is(" (default temp_c)"));
  cmd->add_option("--gyro-col", c.gyro, "Name of the gyro output column, or several A,B,C" + is(" (default gyro_dph)"));
  cmd->add_option("--temp2-col", c.temp2, "Name of the far-side temperature column, for the grad term" + is(" (default temp2_c)"));
  fit::Units& u = c.units;
  using fit::Quantity;
  const std::string header = fit_defaults ? " (default: the fit's)"
                                          : " (default: the unit the column's name states, e.g. 'time (ms)', else ";
  const auto last = [&](const char* base) { return fit_defaults ? std::string() : std::string(base) + ")"; };
  cmd->add_option("--time-unit", u.time, "Unit of the time column: " + fit::unit_names(Quantity::time, " or ") + header + last("s"));
  cmd->add_option("--gyro-unit", u.gyro, "Unit of the gyro column: " + fit::unit_names(Quantity::gyro, " or ") + header + last("dph"));
  cmd->add_option("--temp-unit", u.temp, "Unit of the temperature columns: " + fit::unit_names(Quantity::temperature, " or ") + header + last("C"));
  cmd->add_option("--gyro-scale", u.gyro_scale,
                  "Multiply the gyro column by K before its unit (raw counts, a logger's scale)" + is(""));
  cmd->add_option("--temp-scale", u.temp_scale,
                  "Temperature = A x column + B (raw counts): A, before --temp-unit" + is(" (default 1)"));
  cmd->add_option("--temp-offset", u.temp_offset, "Temperature = A x column + B: B" + is(" (default 0)"));
  cmd->add_option("--delimiter", c.csv.delimiter,
                  "Column delimiter: comma, semicolon, tab or auto" + is(" (default auto: the one the header uses)"));
  cmd->add_flag("--decimal-comma", c.csv.decimal_comma, "Numbers are written with a decimal comma (20,5)" + is(""));
  cmd->add_option("--imu", c.imu,
                  "The gyro instance of a PX4 ULog or ArduPilot DataFlash log" + is(" (default: the first with a temperature)"));
  cmd->add_option("--rate", c.csv.rate_hz,
                  "Sample rate in Hz of a log without a time column (row k at k / rate s)" + is(""));
}

void add_data_options(CLI::App* cmd, DataOptions& o, bool with_avg) {
  if (with_avg)
    cmd->add_option("--avg", o.pipeline.averaging.window_s,
                    "Averaging window in seconds (default 100, the paper's 100 s averages)");
  cmd->add_option("--deriv-span", o.pipeline.derivative_span_s,
                  "Longest time between two window centres that dT/dt and d2T/dt2 may span, "
                  "across a gap or not (default 600 s)");
  cmd->add_flag("--causal", o.causal,
                "Backward differences for dT/dt and d2T (a real-time compensator); default central");
  cmd->add_flag("--keep-outliers", o.keep_outliers, "Do not remove counting glitches");
  cmd->add_option("--outlier-threshold", o.outlier_threshold,
                  "Glitch rule: deviation from the moving median in robust sigmas (default 8)");
  add_column_options(cmd, o.pipeline.columns, false);
}

std::vector<const fit::Term*> ModelOptions::base_terms() const { return fit::parse_formula(model); }

std::vector<const fit::Term*> ModelOptions::terms() const {
  std::string formula = model;
  for (const std::string& a : add) formula += " + " + a;
  return fit::parse_formula(formula);  // refuses a term given twice
}

void add_model_options(CLI::App* cmd, ModelOptions& o, const std::string& add_help) {
  cmd->add_option("--model", o.model, "Model formula, terms joined by + (default 'T + T^2 + dT')");
  cmd->add_option("--add", o.add, add_help);
  cmd->add_option("--engine", o.engine, "Fitting engine (default ols; see 'gyrotherm engines')");
  cmd->add_option("--seed", o.seed, "Seed of a stochastic engine and of ols's bootstrap intervals (default 1)");
}

}  // namespace gyrotherm::app
