#include "fit/fit_file.h"

#include <algorithm>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <tuple>
#include <nlohmann/json.hpp>

#include "fit/model/formula.h"
#include "fit/record_support.h"
#include "sim/util/input_error.h"
#include "sim/util/json_fields.h"

namespace gyrotherm::fit {
namespace {

using Json = nlohmann::ordered_json;
using json_fields::field;
using json_fields::field_at;
using json_fields::finite;
using json_fields::finite_at;
using json_fields::finite_number;
using json_fields::read_object;

}  // namespace

void to_json(nlohmann::ordered_json& j, const CsvDialect& c) {
  j = {{"delimiter", c.delimiter.empty() ? "auto" : c.delimiter},
       {"decimal_comma", c.decimal_comma},
       {"rate_hz", c.rate_hz}};
}

void from_json(const nlohmann::json& j, CsvDialect& c) {
  c.delimiter = field(j, "delimiter", "comma, semicolon, tab or auto").get<std::string>();
  c.decimal_comma = field(j, "decimal_comma", "true or false").get<bool>();
  c.rate_hz = finite(j, "rate_hz", "Hz");
  c.validate();
}

void to_json(nlohmann::ordered_json& j, const Units& u) {
  j = {{"time", u.time_unit().name},
       {"gyro", u.gyro_unit().name},
       {"temp", u.temp_unit().name},
       {"gyro_scale", u.gyro_scale},
       {"temp_scale", u.temp_scale},
       {"temp_offset", u.temp_offset},
       {"conversion", u.description()},
       {"from", {{"time", u.time_from}, {"gyro", u.gyro_from}, {"temp", u.temp_from}}}};
  if (!u.kind().is_gyro) j["sensor"] = u.kind().name;  // (a gyro's fit file is as it was)
}

void from_json(const nlohmann::json& j, Units& u) {
  u.sensor = j.contains("sensor") ? field(j, "sensor", sensor_kind_names()).get<std::string>() : std::string();
  u.time = field(j, "time", unit_names(Quantity::time, " or ")).get<std::string>();
  u.gyro = field(j, "gyro", unit_names(u.kind().quantity, " or ")).get<std::string>();
  u.temp = field(j, "temp", unit_names(Quantity::temperature, " or ")).get<std::string>();
  u.gyro_scale = finite(j, "gyro_scale", "a number");
  u.temp_scale = finite(j, "temp_scale", "a number");
  u.temp_offset = finite(j, "temp_offset", "a number");
  // Where each unit came from when fitting: only a typed one (an option) is
  // given; one its record's header or the default gave yields to the header
  // of the record it is applied to. (Fit files without "from": all given.)
  const nlohmann::json* from = j.contains("from") && j["from"].is_object() ? &j["from"] : nullptr;
  for (auto [key, text, weak] : {std::tuple{"time", &u.time_from, &u.time_weak},
                                 {"gyro", &u.gyro_from, &u.gyro_weak},
                                 {"temp", &u.temp_from, &u.temp_weak}}) {
    text->clear();
    if (from == nullptr || !from->contains(key) || !(*from)[key].is_string()) continue;
    const std::string origin = (*from)[key].get<std::string>();
    *weak = !origin.starts_with("--");
    *text = fmt::format(", {} when fitting", origin.empty() ? "default" : origin);
  }
}

void to_json(nlohmann::ordered_json& j, const ColumnMap& c) {
  j = {{"time", c.time},
       {"temp", c.temp},
       {"gyro", c.gyro},
       {"temp2", c.temp2},
       {"imu", c.imu ? nlohmann::ordered_json(*c.imu) : nlohmann::ordered_json()},
       {"csv", c.csv},
       {"units", c.units}};
}

void from_json(const nlohmann::json& j, ColumnMap& c) {
  c.time = field(j, "time", "name").get<std::string>();
  c.temp = field(j, "temp", "name").get<std::string>();
  c.gyro = field(j, "gyro", "name").get<std::string>();
  c.temp2 = field(j, "temp2", "name").get<std::string>();
  if (j.contains("imu") && !j["imu"].is_null()) {
    const double imu = finite(j, "imu", "a gyro instance");
    if (imu != std::floor(imu) || imu < 0 || imu > 255)
      throw InputError(fmt::format("imu: {} is not a gyro instance (0..255)", imu));
    c.imu = static_cast<int>(imu);
  }
  // Fit files from before the CSV forms and the units were options have none: the defaults.
  if (j.contains("csv")) read_object(j, "csv", "the CSV form", c.csv);
  if (j.contains("units")) read_object(j, "units", "the units", c.units);
}

void to_json(nlohmann::ordered_json& j, const PipelineOptions& p) {
  j = {{"avg_s", p.averaging.window_s},
       {"derivative", to_string(p.derivative)},
       {"deriv_span_s", p.derivative_span_s},
       {"remove_outliers", p.remove_outliers},
       {"outlier_window_s", p.outliers.window_s},
       {"outlier_threshold", p.outliers.threshold},
       {"columns", p.columns}};
  // A sensor lag given when fitting (--sensor-tau): compensate reads the temperatures the same way.
  if (p.sensor_tau_s > 0.0) j["sensor_tau_s"] = p.sensor_tau_s;
}

void from_json(const nlohmann::json& j, PipelineOptions& p) {
  p.averaging.window_s = finite(j, "avg_s", "the averaging window");
  const std::string mode = field(j, "derivative", "central or causal").get<std::string>();
  if (mode != "central" && mode != "causal")
    throw InputError(fmt::format("derivative = '{}': expected 'central' or 'causal'", mode));
  p.derivative = mode == "causal" ? DerivativeMode::causal : DerivativeMode::central;
  // Fit files from before derivatives bridged gaps have no span: the default.
  if (j.contains("deriv_span_s")) p.derivative_span_s = finite(j, "deriv_span_s", "s");
  if (j.contains("sensor_tau_s")) {
    p.sensor_tau_s = finite(j, "sensor_tau_s", "s");
    if (!(p.sensor_tau_s >= 0.0))
      throw InputError(fmt::format("sensor_tau_s: {} must be >= 0 (seconds)", p.sensor_tau_s));
  }
  p.remove_outliers = field(j, "remove_outliers", "true or false").get<bool>();
  p.outliers.window_s = finite(j, "outlier_window_s", "s");
  p.outliers.threshold = finite(j, "outlier_threshold", "MADs");
  read_object(j, "columns", "column names", p.columns);
}

nlohmann::ordered_json noise_model_json(const NoiseModel& n) {
  Json components = Json::object();
  for (const NoiseParameter& q : n.parameters())
    components[q.name] = {{"value", q.value},
                          {"interval_95", {q.lower, q.upper}},
                          {"identified", q.identified},
                          {"unit", q.unit}};
  const bool gyro = n.sensor == nullptr || n.sensor->is_gyro;
  return {{"method", fmt::format("REML on the fit's residual: white + flicker + {} random walk, a "
                                 "Gauss-Markov process where it pays",
                                 gyro ? "rate" : "bias")},
          {"blocks", n.blocks},
          {"block_s", n.block_s},
          {"alternatives", n.alternatives.size()},
          {"components", components}};
}

nlohmann::ordered_json fit_json(const ModelFit& fit, const PreparedData& data,
                                const PipelineOptions& pipeline, const EngineSettings& settings) {
  Json j;
  j["engine"] = fit.engine.engine;
  j["model"] = formula_text(fit.terms);
  if (const SensorKind& kind = data.units.kind(); !kind.is_gyro) {
    // Another sensor's fit: the coefficients and the *_dph fields are in its
    // base unit, named here (a gyro's file is as it always was).
    j["sensor"] = kind.name;
    j["unit"] = kind.unit;
  }
  Json coefficients;
  coefficients["1"] = fit.coefficients.intercept;
  for (std::size_t k = 0; k < fit.terms.size(); ++k)
    coefficients[fit.terms[k]->name] = fit.coefficients.b[k];
  j["coefficients"] = coefficients;
  Json parameters = Json::object();
  for (std::size_t k = 0; k < fit.terms.size(); ++k)
    if (fit.terms[k]->parameter)
      parameters[fit.terms[k]->name] = {{fit.terms[k]->parameter->name, fit.parameters[k]}};
  j["parameters"] = parameters;
  Json parameter_intervals = Json::object();
  for (std::size_t k = 0; k < fit.terms.size(); ++k)
    if (k < fit.parameter_intervals.size() && fit.parameter_intervals[k])
      parameter_intervals[fit.terms[k]->name] = {
          {fit.terms[k]->parameter->name,
           {fit.parameter_intervals[k]->lower, fit.parameter_intervals[k]->upper}}};
  if (!parameter_intervals.empty()) j["parameter_intervals_95"] = parameter_intervals;
  j["instability_before_dph"] = fit.instability_before_dph;
  j["instability_after_dph"] = fit.instability_after_dph;
  j["ratio"] = fit.ratio();
  j["objective"] = fit.engine.objective;
  j["optimum_dph"] = fit.optimum_dph;
  j["gap"] = fit.instability_after_dph / fit.optimum_dph - 1.0;
  j["evaluations"] = fit.engine.evaluations;
  j["iterations"] = fit.engine.iterations;
  j["seconds"] = fit.engine.seconds;
  j["termination"] = to_string(fit.engine.termination);
  j["message"] = run_text(fit.engine);
  j["seed"] = settings.seed;
  j["warnings"] = fit_warnings(fit);
  Json history = Json::array();
  for (const HistoryPoint& h : fit.engine.history) history.push_back({h.evaluations, h.best_objective});
  j["history"] = history;
  if (!fit.engine.inference.intervals.empty()) {
    Json intervals;
    for (std::size_t k = 0; k < fit.terms.size(); ++k)
      intervals[fit.terms[k]->name] = {fit.engine.inference.intervals[k].lower, fit.engine.inference.intervals[k].upper};
    j["intervals_95"] = intervals;
    j["interval_method"] =
        interval_method_text(fit.engine.inference.interval_method, fit.noise ? &fit.noise->model : nullptr);
    j["interval_kind"] = to_string(fit.engine.inference.interval_method.kind);
    if (!fit.lag_sensitivity.empty()) {
      // The sensor lag (s) that would move each rate or gradient term by its half-width (null: none would).
      Json lag;
      for (const LagSensitivity& l : fit.lag_sensitivity)
        lag[fit.terms[l.term]->name] = std::isfinite(l.lag_s) ? Json(l.lag_s) : Json(nullptr);
      j["lag_to_move_by_interval_s"] = lag;
    }
  }
  if (fit.noise) j["noise_model"] = noise_model_json(fit.noise->model);
  {
    const RecordSupport& s = fit.support;
    Json flags = Json::object(), reasons = Json::object();
    for (std::size_t k = 0; k < fit.terms.size() && k < s.flags.size(); ++k)
      if (!s.flags[k].empty()) flags[fit.terms[k]->name] = s.flags[k];
    for (std::size_t k = 0; k < fit.terms.size() && k < s.reasons.size(); ++k)
      if (!s.reasons[k].empty()) {
        Json list = Json::array();
        for (SupportReason r : s.reasons[k]) list.push_back(to_string(r));
        reasons[fit.terms[k]->name] = list;
      }
    j["record"] = {{"temp_range_c", {s.temp_min_c, s.temp_max_c}},
                   {"temperature_levels", s.temperature_levels},
                   {"level_width_c", s.level_width_c},
                   {"largest_gap_c", {s.gap_from_c, s.gap_to_c}},
                   {"temp_time_correlation", s.temp_time_correlation},
                   {"flags", flags},
                   {"reasons", reasons}};
  }
  if (!fit.engine.inference.p_values.empty()) {
    Json p;
    for (std::size_t k = 0; k < fit.terms.size(); ++k) p[fit.terms[k]->name] = fit.engine.inference.p_values[k];
    j["p_values"] = p;
  }
  if (!fit.engine.inference.kept.empty()) {
    Json kept = Json::array();
    for (std::size_t k = 0; k < fit.terms.size(); ++k)
      if (fit.engine.inference.kept[k]) kept.push_back(fit.terms[k]->name);
    j["kept"] = kept;
  }
  Json gaps = Json::array();
  for (const Gap& g : data.averaging.gaps) gaps.push_back({g.from_s, g.to_s});
  Json outlier_times = Json::array();
  for (std::size_t k = 0; k < data.outliers.times_s.size() && k < 100; ++k)
    outlier_times.push_back(data.outliers.times_s[k]);
  j["data"] = {{"file", data.file},
               {"raw_samples", data.raw_samples},
               {"sample_interval_s", data.averaging.sample_interval_s},
               {"outliers_removed", data.outliers.removed},
               {"outlier_times_s", outlier_times},
               {"gaps", gaps},
               {"windows", data.series.size()},
               {"dropped_windows", data.averaging.dropped_windows},
               {"bursts", data.averaging.bursts},
               {"windows_described", describe_windows(data, pipeline)},
               {"units", data.units.used()},
               {"cautions", caution_texts(data.cautions)}};
  j["data"]["outlier_floor_dph"] = data.outliers.floor_dph;  // the glitch rule's s_floor on this record
  if (!data.series.temp_c.empty()) {
    const auto [lo, hi] = std::minmax_element(data.series.temp_c.begin(), data.series.temp_c.end());
    j["data"]["temp_range_c"] = {*lo, *hi};  // of the window means: where the model was fitted
  }
  PipelineOptions written = pipeline;
  written.columns.units = data.units;  // the units the record was read in, each set
  j["pipeline"] = written;
  return j;
}

nlohmann::ordered_json channels_json(
    const std::vector<std::pair<std::string, nlohmann::ordered_json>>& channels) {
  Json list = Json::array();
  for (const auto& [name, object] : channels) {
    Json entry;
    entry["channel"] = name;
    for (const auto& [key, value] : object.items()) entry[key] = value;
    list.push_back(entry);
  }
  return Json{{"channels", list}};
}

namespace {
nlohmann::json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": no such file (a fit saved with 'gyrotherm fit -o')");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not a fit file: not JSON ({}); give the file 'gyrotherm fit -o' writes",
                                 file.string(), e.what()));
  }
  return j;
}

// The coefficients and parameters of the fit's terms (path-named errors).
void read_terms(const nlohmann::json& j, SavedFit& s) {
  s.engine = field(j, "engine", "the engine's name").get<std::string>();
  s.terms = parse_formula(field(j, "model", "the model formula").get<std::string>());  // its errors name the model
  const nlohmann::json& coefficients = field(j, "coefficients", "term -> value");
  s.coefficients.intercept = finite_at(coefficients, "1", "coefficients.1", "the intercept");
  for (const Term* t : s.terms) {
    const std::string name(t->name);
    s.coefficients.b.push_back(finite_at(coefficients, name, "coefficients." + name, "a model term's coefficient"));
  }
  s.parameters = default_parameters(s.terms);
  for (std::size_t k = 0; k < s.terms.size(); ++k) {
    if (!s.terms[k]->parameter) continue;
    const std::string name(s.terms[k]->name), parameter(s.terms[k]->parameter->name);
    const nlohmann::json& p = field_at(field(j, "parameters", "nonlinear term parameters"), name,
                                       "parameters." + name, "the term's parameter");
    s.parameters[k] = finite_at(p, parameter, "parameters." + name + "." + parameter, "the parameter value");
  }
}

// What the fit file says of its data: the range, the file, the sample
// interval, the glitch floor, the burst mode (each absent in older files).
void read_data(const nlohmann::json& j, SavedFit& s) {
  if (!j.contains("data") || !j["data"].is_object()) return;
  const nlohmann::json& d = j["data"];
  if (d.contains("temp_range_c")) {
    const nlohmann::json& r = d["temp_range_c"];
    if (!r.is_array() || r.size() != 2) throw InputError("data.temp_range_c: expected [min, max] in °C");
    s.temp_range_c = {finite_number(r[0], "data.temp_range_c[0]", "°C"), finite_number(r[1], "data.temp_range_c[1]", "°C")};
  }
  if (d.contains("file") && d["file"].is_string()) s.data_file = d["file"].get<std::string>();
  if (d.contains("sha256") && d["sha256"].is_string()) s.data_sha256 = d["sha256"].get<std::string>();
  if (d.contains("cautions") && d["cautions"].is_array())
    for (const nlohmann::json& c : d["cautions"])
      if (c.is_string()) s.data_cautions.push_back(c.get<std::string>());
  if (d.contains("sample_interval_s"))
    s.sample_interval_s = finite_number(d["sample_interval_s"], "data.sample_interval_s", "s");
  if (d.contains("outlier_floor_dph"))
    s.outlier_floor_dph = finite_number(d["outlier_floor_dph"], "data.outlier_floor_dph", "°/h");
  if (d.contains("bursts") && d["bursts"].is_boolean()) s.bursts = d["bursts"].get<bool>();
}

// The terms the record could not support over its range, with why (fit
// files from before record.reasons have none).
void read_record(const nlohmann::json& j, SavedFit& s) {
  if (j.contains("record") && j["record"].is_object() && j["record"].contains("reasons")) {
    const nlohmann::json& record = j["record"];
    const nlohmann::json& reasons = record["reasons"];
    if (!reasons.is_object())
      throw InputError("record.reasons: expected {term: [reason, ...]}");
    for (const auto& [term, list] : reasons.items()) {
      bool limits = false;
      for (const nlohmann::json& r : list.is_array() ? list : nlohmann::json::array()) {
        bool known = false;
        for (int k = 0; k < kSupportReasons; ++k)
          if (r.is_string() && r.get<std::string>() == to_string(static_cast<SupportReason>(k))) {
            known = true;
            limits = limits || limits_range(static_cast<SupportReason>(k));
          }
        if (!known)
          throw InputError(fmt::format("record.reasons.{}: expected a list of narrow_range, few_levels, gap, "
                                       "time_locked",
                                       term));
      }
      const nlohmann::json* why = record.contains("flags") && record["flags"].contains(term) ? &record["flags"][term] : nullptr;
      (limits ? s.support_flags : s.meaning_flags)
          .emplace_back(term, why && why->is_string() ? why->get<std::string>() : list.dump());
    }
  }
}

SavedFit load_fit_unchecked(const std::filesystem::path& file, const nlohmann::json& j, FitKinds kinds) {
  SavedFit s;
  s.file = file;
  try {
    read_terms(j, s);
    read_object(j, "pipeline", "how the data were prepared", s.pipeline);
    s.instability_after_dph = finite(j, "instability_after_dph", "°/h");
    if (j.contains("instability_before_dph"))
      s.instability_before_dph = finite_number(j["instability_before_dph"], "instability_before_dph", "°/h");
    read_data(j, s);
    read_record(j, s);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}; is this a file written by 'gyrotherm fit -o'?", file.string(), e.what()));
  }
  // The units read are the fit's: said so where a report says where a unit
  // came from, before where it came from when fitting.
  if (j["pipeline"]["columns"].contains("units")) {
    Units& units = s.pipeline.columns.units;
    units.set_from_fit(file.string());
    try {
      units.validate();
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: pipeline.columns.units: {}", file.string(), e.what()));
    }
  }
  // Another sensor's fit, by its units (a gyro's when it has none) or by its
  // top-level "sensor": not applied as a gyro's, and the two must agree.
  const SensorKind& kind = s.pipeline.columns.units.kind();
  if (kinds == FitKinds::any) {
    const std::string top = j.contains("sensor") && j["sensor"].is_string() ? j["sensor"].get<std::string>() : "gyro";
    if (top != kind.name)
      throw InputError(fmt::format("{}: its \"sensor\" is \"{}\" but pipeline.columns.units.sensor is {}: the fit "
                                   "file was edited; fit again",
                                   file.string(), top, kind.name));
    return s;
  }
  if (!kind.is_gyro)
    throw InputError(fmt::format("{}: pipeline.columns.units.sensor is {} (the {}'s fit): report "
                                 "takes a gyro's fit only, so far (compensate, check, allan --fit and export take it)",
                                 file.string(), kind.name, kind.noun));
  if (j.contains("sensor") && j["sensor"] != "gyro")
    throw InputError(fmt::format("{}: the fit of a sensor of kind {} (its \"sensor\"): report "
                                 "takes a gyro's fit only, so far (compensate, check, allan --fit and export take it)",
                                 file.string(), j["sensor"].dump()));
  return s;
}
}  // namespace

std::vector<SavedFit> load_fits(const std::filesystem::path& file, FitKinds kinds) {
  return load_fits_json(read_json(file), file, kinds);
}

std::vector<SavedFit> load_fits_json(const nlohmann::json& j, const std::filesystem::path& file, FitKinds kinds) {
  try {
    if (!j.is_object() || !j.contains("channels")) return {load_fit_unchecked(file, j, kinds)};
    if (!j["channels"].is_array() || j["channels"].empty())
      throw InputError(fmt::format("{}: channels: expected a list of fits", file.string()));
    std::vector<SavedFit> fits;
    for (const nlohmann::json& c : j["channels"]) {
      SavedFit s = load_fit_unchecked(file, c, kinds);
      s.channel = c.contains("channel") && c["channel"].is_string() ? c["channel"].get<std::string>()
                                                                   : s.pipeline.columns.gyro;
      fits.push_back(std::move(s));
    }
    return fits;
  } catch (const nlohmann::json::exception& e) {
    // A field of the wrong type (a number where a string belongs, say).
    throw InputError(fmt::format("{}: a field has the wrong type ({})", file.string(), e.what()));
  }
}

void check_given_sensor(const SavedFit& fit, const std::string& given_sensor) {
  const SensorKind& kind = fit.pipeline.columns.units.kind();
  if (!given_sensor.empty() && &sensor_kind(given_sensor) != &kind)
    throw InputError(fmt::format("--sensor {}: {} is the {}'s fit (--sensor {}); leave --sensor out, or give that "
                                 "sensor's fit",
                                 given_sensor, fit.file.string(), kind.noun, kind.name));
}

SavedFit load_fit(const std::filesystem::path& file) {
  std::vector<SavedFit> fits = load_fits(file);
  if (fits.size() != 1)
    throw InputError(fmt::format("{}: holds {} channels; one was expected", file.string(), fits.size()));
  return std::move(fits.front());
}

}  // namespace gyrotherm::fit
