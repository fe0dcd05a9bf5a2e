#include "studies/options/pipeline_options.h"

#include <fmt/format.h>

#include <cmath>

#include "sim/util/input_error.h"

namespace gyrotherm::studies {

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
  if (!(p.sensor_tau_s >= 0.0) || !std::isfinite(p.sensor_tau_s))
    throw InputError(fmt::format("--sensor-tau {}: must be a number of seconds >= 0 (0: the sensors do not lag)",
                                 p.sensor_tau_s));
  if (causal) p.derivative = fit::DerivativeMode::causal;
  if (keep_outliers) p.remove_outliers = false;
  return p;
}

std::vector<OptionRow<fit::ColumnMap>> column_option_rows(bool fit_defaults) {
  using C = fit::ColumnMap;
  using fit::Quantity;
  const auto is = [&](const std::string& plain) { return fit_defaults ? std::string(" (default: the fit's)") : plain; };
  // The default: the fit's, or the unit the column's name states ("time (ms)", "gyro [rad/s]"), else the base.
  const auto unit_help = [&](const char* what, Quantity q, const char* example, const char* base) {
    return fmt::format("Unit of the {}: {}{}", what, fit::unit_names(q, " or "),
                       fit_defaults ? std::string(" (default: the fit's)")
                                    : fmt::format(" (default: the unit the column's name states, e.g. '{}', else {})",
                                                  example, base));
  };
  return {
      field_row<C>("--time-col", "Name of the time column" + is(" (default time_s)"), &C::time),
      field_row<C>("--temp-col", "Name of the gyro temperature column" + is(" (default temp_c)"), &C::temp),
      field_row<C>("--gyro-col", "Name of the gyro output column, or several A,B,C" + is(" (default gyro_dph)"), &C::gyro),
      field_row<C>("--temp2-col", "Name of the far-side temperature column, for the grad term" + is(" (default temp2_c)"),
                   &C::temp2),
      nested_row("--time-unit", unit_help("time column", Quantity::time, "time (ms)", "s"), &C::units, &fit::Units::time),
      nested_row("--gyro-unit", unit_help("gyro column", Quantity::gyro, "gyro [rad/s]", "dph"), &C::units, &fit::Units::gyro),
      nested_row("--temp-unit", unit_help("temperature columns", Quantity::temperature, "temp (K)", "C"),
                 &C::units, &fit::Units::temp),
      nested_row("--gyro-scale", "Multiply the gyro column by K before its unit (raw counts, a logger's scale)" + is(""),
                 &C::units, &fit::Units::gyro_scale),
      nested_row("--temp-scale", "Temperature = A x column + B (raw counts): A, before --temp-unit" + is(" (default 1)"),
                 &C::units, &fit::Units::temp_scale),
      nested_row("--temp-offset", "Temperature = A x column + B: B" + is(" (default 0)"),
                 &C::units, &fit::Units::temp_offset),
      nested_row("--delimiter", "Column delimiter: comma, semicolon, tab or auto" + is(" (default auto: the one the header uses)"),
                 &C::csv, &fit::CsvDialect::delimiter),
      nested_row("--decimal-comma", "Numbers are written with a decimal comma (20,5)" + is(""),
                 &C::csv, &fit::CsvDialect::decimal_comma),
      field_row<C>("--imu", "The gyro instance of a PX4 ULog or ArduPilot DataFlash log" + is(" (default: the first with a temperature)"),
                   &C::imu),
      nested_row("--rate", "Sample rate in Hz of a log without a time column (row k at k / rate s)" + is(""),
                 &C::csv, &fit::CsvDialect::rate_hz),
  };
}

std::vector<OptionRow<DataOptions>> data_option_rows(bool with_avg) {
  using D = DataOptions;
  std::vector<OptionRow<D>> rows;
  if (with_avg)
    rows.push_back(field_row<D>("--avg", "Averaging window in seconds (default 100, the paper's 100 s averages)",
                                [](D& o) -> auto& { return o.pipeline.averaging.window_s; }));
  rows.push_back(field_row<D>("--deriv-span",
                              "Longest time between two window centres that dT/dt and d2T/dt2 may span, "
                              "across a gap or not (default 600 s)",
                              [](D& o) -> auto& { return o.pipeline.derivative_span_s; }));
  rows.push_back(field_row<D>("--sensor-tau",
                              "Time constant in s of the temperature sensors' lag behind the gyro's temperature: "
                              "temperatures are read as T + tau dT/dt (default 0: no lag)",
                              [](D& o) -> auto& { return o.pipeline.sensor_tau_s; }));
  rows.push_back(field_row<D>("--causal", "Backward differences for dT/dt and d2T (a real-time compensator); default central",
                              &D::causal));
  rows.push_back(field_row<D>("--keep-outliers", "Do not remove counting glitches", &D::keep_outliers));
  rows.push_back(field_row<D>("--outlier-threshold",
                              "Glitch rule: deviation from the moving median in robust sigmas (default 8)",
                              &D::outlier_threshold));
  append_rows(rows, column_option_rows(false), [](D& o) -> auto& { return o.pipeline.columns; });
  return rows;
}

std::vector<GivenOption> given_data_options(const fit::PipelineOptions& pipeline) {
  DataOptions d;
  d.pipeline = pipeline;
  d.causal = pipeline.derivative == fit::DerivativeMode::causal;
  d.pipeline.derivative = fit::DerivativeMode::central;
  d.keep_outliers = !pipeline.remove_outliers;
  d.pipeline.remove_outliers = true;
  if (pipeline.remove_outliers && pipeline.outliers.threshold != fit::OutlierOptions{}.threshold)
    d.outlier_threshold = pipeline.outliers.threshold;
  return given_options(data_option_rows(true), d);
}

std::vector<const fit::Term*> ModelOptions::base_terms() const { return fit::parse_formula(model); }

std::vector<const fit::Term*> ModelOptions::terms() const {
  std::string formula = model;
  for (const std::string& a : add) formula += " + " + a;
  return fit::parse_formula(formula);  // refuses a term given twice
}

ModelRequest model_request(const ModelOptions& model, const DataOptions& data,
                           const std::function<fit::EngineSettings()>& settings) {
  ModelRequest r;
  r.terms = model.terms();
  const fit::EngineInfo& engine = fit::find_engine(model.engine);  // its errors first, then the settings'
  r.settings = settings();
  engine.make(r.settings);
  r.pipeline = data.resolved();
  return r;
}

std::vector<OptionRow<ModelOptions>> model_option_rows(const std::string& add_help) {
  using M = ModelOptions;
  return {
      field_row<M>("--model", "Model formula, terms joined by + (default 'T + T^2 + dT')", &M::model),
      field_row<M>("--add", add_help, &M::add),
      field_row<M>("--engine", "Fitting engine (default ols; see 'gyrotherm engines')", &M::engine),
      field_row<M>("--seed", "Seed of a stochastic engine and of ols's bootstrap intervals (default 1)", &M::seed),
  };
}

}  // namespace gyrotherm::studies
