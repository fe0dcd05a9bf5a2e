#include "studies/options/pipeline_options.h"

#include <fmt/format.h>

#include "sim/util/input_error.h"

namespace gyrotherm::studies {

fit::PipelineOptions DataOptions::resolved() const {
  fit::PipelineOptions p = pipeline;
  p.columns.units.validate();
  if (keep_outliers && outlier_threshold)
    throw InputError("--keep-outliers and --outlier-threshold contradict each other: keep the "
                     "glitches, or set the rule that removes them, not both");
  // --deriv-span, --sensor-tau, --outlier-threshold: their rows' rules.
  static const OptionTable<DataOptions> rows{"", data_option_rows(true)};
  check_rules(rows, *this);
  if (outlier_threshold) p.outliers.threshold = *outlier_threshold;
  if (causal) p.derivative = fit::DerivativeMode::causal;
  if (keep_outliers) p.remove_outliers = false;
  return p;
}

void require_gyro(const fit::ColumnMap& columns, std::string_view command) {
  const fit::SensorKind& kind = columns.units.kind();
  if (!kind.is_gyro)
    throw InputError(fmt::format("--sensor {}: {} reads a gyro only, so far; `gyrotherm fit --sensor {}` fits the {}'s "
                                 "channel",
                                 kind.name, command, kind.name, kind.noun));
}

std::vector<OptionRow<fit::ColumnMap>> column_option_rows(bool fit_defaults) {
  using C = fit::ColumnMap;
  using fit::Quantity;
  // The default: the fit's (compensate), a rule in words, or a default map's
  // value (a command that keeps its own map unset until given shows that).
  const auto note = [&](OptionRow<C> row, const std::string& rule = {}) {
    if (fit_defaults) return defaulting(std::move(row), "the fit's");
    if (!rule.empty()) return defaulting(std::move(row), rule);
    const std::string value = value_default(row, fit::ColumnMap{});
    return value.empty() ? row : defaulting(std::move(row), value);
  };
  const auto unit_row = [&](const char* names, const char* what, Quantity q, const char* example, const char* base,
                            std::string fit::Units::*field) {
    return note(nested_row(names, fmt::format("Unit of the {}: {}", what, fit::unit_names(q, " or ")), &C::units, field),
                fmt::format("the unit the column's name states, e.g. '{}', else {}", example, base));
  };
  return {
      note(field_row<C>("--time-col", "Name of the time column", &C::time)),
      note(field_row<C>("--temp-col", "Name of the gyro temperature column", &C::temp)),
      note(field_row<C>("--gyro-col", "Name of the gyro output column, or several A,B,C", &C::gyro),
           "gyro_dph (accel_mps2, baro_pa, mag_gauss with --sensor)"),
      note(field_row<C>("--temp2-col", "Name of the far-side temperature column, for the grad term", &C::temp2)),
      unit_row("--time-unit", "time column", Quantity::time, "time (ms)", "s", &fit::Units::time),
      note(nested_row("--sensor",
                      fmt::format("The kind of sensor the gyro column is: {} (an accelerometer's column in "
                                  "m/s², a barometer's in Pa, a magnetometer's in gauss; --gyro-col, --gyro-unit "
                                  "and --gyro-scale then name its column, unit and scale)",
                                  fit::sensor_kind_names()),
                      &C::units, &fit::Units::sensor),
           "gyro"),
      note(nested_row("--gyro-unit",
                      fmt::format("Unit of the gyro column: {}; of an accelerometer's: {}; of a barometer's: {}; "
                                  "of a magnetometer's: {}",
                                  fit::unit_names(Quantity::gyro, " or "), fit::unit_names(Quantity::accel, " or "),
                                  fit::unit_names(Quantity::pressure, " or "),
                                  fit::unit_names(Quantity::magnetic, " or ")),
                      &C::units, &fit::Units::gyro),
           "the unit the column's name states, e.g. 'gyro [rad/s]', else dph (mps2, Pa, gauss)"),
      unit_row("--temp-unit", "temperature columns", Quantity::temperature, "temp (K)", "C", &fit::Units::temp),
      note(nested_row("--gyro-scale", "Multiply the gyro column by K before its unit (raw counts, a logger's scale)",
                      &C::units, &fit::Units::gyro_scale)),
      note(nested_row("--temp-scale", "Temperature = A x column + B (raw counts): A, before --temp-unit", &C::units,
                      &fit::Units::temp_scale)),
      note(nested_row("--temp-offset", "Temperature = A x column + B: B", &C::units, &fit::Units::temp_offset)),
      note(nested_row("--delimiter", "Column delimiter: comma, semicolon, tab or auto (the one the header uses)",
                      &C::csv, &fit::CsvDialect::delimiter),
           "auto"),
      note(nested_row("--decimal-comma", "Numbers are written with a decimal comma (20,5)", &C::csv,
                      &fit::CsvDialect::decimal_comma)),
      note(field_row<C>("--imu", "The instance of the sensor (--sensor) in a PX4 ULog or ArduPilot DataFlash log", &C::imu),
           "the first with a temperature"),
      note(nested_row("--rate", "Sample rate in Hz of a log without a time column (row k at k / rate s)", &C::csv,
                      &fit::CsvDialect::rate_hz),
           "a time column"),
  };
}

std::vector<OptionRow<DataOptions>> data_option_rows(bool with_avg) {
  using D = DataOptions;
  std::vector<OptionRow<D>> rows;
  if (with_avg)
    rows.push_back(field_row<D>("--avg", "Averaging window in seconds (the paper's 100 s averages)",
                                [](D& o) -> auto& { return o.pipeline.averaging.window_s; }));
  rows.push_back(ruled_row<D>("--deriv-span",
                              "Longest time between two window centres that dT/dt and d2T/dt2 may span, "
                              "across a gap or not",
                              [](D& o) -> auto& { return o.pipeline.derivative_span_s; }, number_above(0.0, kNoBound, "s")));
  rows.push_back(ruled_row<D>("--sensor-tau",
                              "Time constant in s of the temperature sensors' lag behind the gyro's temperature: "
                              "temperatures are read as T + tau dT/dt (0: no lag)",
                              [](D& o) -> auto& { return o.pipeline.sensor_tau_s; }, number_in(0.0, kNoBound, "s")));
  rows.push_back(field_row<D>("--causal", "Backward differences for dT/dt and d2T (a real-time compensator) rather than central ones",
                              &D::causal));
  rows.push_back(field_row<D>("--keep-outliers", "Do not remove counting glitches", &D::keep_outliers));
  // (Unset until given: the glitch rule's own threshold applies.)
  rows.push_back(defaulting(ruled_row<D>("--outlier-threshold",
                                         "Glitch rule: deviation from the moving median in robust sigmas",
                                         &D::outlier_threshold, number_above(0.0, kNoBound)),
                            detail::number_text(fit::OutlierOptions{}.threshold)));
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
      field_row<M>("--model", "Model formula, terms joined by +", &M::model),
      field_row<M>("--add", add_help, &M::add),
      field_row<M>("--engine", "Fitting engine (see 'gyrotherm engines')", &M::engine),
      field_row<M>("--seed", "Seed of a stochastic engine and of ols's bootstrap intervals", &M::seed),
  };
}

}  // namespace gyrotherm::studies
