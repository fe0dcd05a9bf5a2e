#include "studies/simulated.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "fit/channels.h"
#include "fit/data/sensor_kind.h"
#include "sim/output.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {

fit::Measurement measurement_of(sim::SimulationResult record, std::string file) {
  fit::Measurement m;
  m.file = std::move(file);
  m.time_s = std::move(record.time_s);
  m.temp_c = std::move(record.temp_c);
  m.gyro_dph = std::move(record.gyro_dph);
  m.temp2_c = std::move(record.temp2_c);
  return m;
}

std::optional<Truth> load_truth_beside(const std::filesystem::path& record, std::string_view column) {
  const std::filesystem::path file = sim::truth_path_for(record);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  std::ifstream in(file);
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", file.string(), e.what()));
  }
  // The truth of another record written beside (imu.csv's, read beside imu.ulg: both imu.truth.json) is not
  // this one's. (By name: a record edited in place keeps its truth.)
  if (j.is_object() && j.contains("record") && j["record"].is_object() && j["record"].contains("file") &&
      j["record"]["file"] != record.filename().string())
    return std::nullopt;
  return channel_truth(j, file, column);
}

std::optional<Truth> channel_truth(const nlohmann::json& j, const std::filesystem::path& file,
                                   std::string_view column) {
  if (!j.is_object() || !j.contains("channels")) return truth_from_json(j, file);
  if (column.empty() || column == "gyro_dph" || column == "gyro_x") {
    Truth t = truth_from_json(j, file);
    t.channel_matched = true;
    return t;
  }
  if (!j["channels"].is_array()) throw InputError(fmt::format("{}: expected an array 'channels'", file.string()));
  for (const nlohmann::json& ch : j["channels"]) {
    if (!ch.is_object() || !ch.contains("sensor") || !ch.contains("column") || !ch.contains("coefficients"))
      throw InputError(fmt::format("{}: each of 'channels' needs sensor, column and coefficients", file.string()));
    // As an autopilot log's reader names it (the kind's log_columns: accel_x, pressure).
    const fit::SensorKind& kind = fit::sensor_kind(ch["sensor"].get<std::string>());
    std::string log_column;
    for (const std::string& c : fit::parse_channels(std::string(kind.log_columns)))
      if (kind.axes() == 1 || c.ends_with("_" + ch.value("axis", std::string()))) log_column = c;
    if (column != ch["column"].get<std::string>() && column != log_column) continue;
    nlohmann::json gyro_like = j;  // the gyro's hidden parameters hold for every channel
    gyro_like["coefficients"] = ch["coefficients"];
    Truth t = truth_from_json(gyro_like, file);
    t.channel_matched = true;
    return t;
  }
  return std::nullopt;
}

Truth truth_from_json(const nlohmann::json& j, const std::filesystem::path& file) {
  if (!j.is_object() || !j.contains("coefficients") || !j["coefficients"].is_object())
    throw InputError(fmt::format("{}: expected an object 'coefficients' (term -> value)",
                                 file.string()));
  Truth t;
  t.file = file;
  for (const auto& [k, v] : j["coefficients"].items()) {
    if (!v.is_number())
      throw InputError(fmt::format("{}: coefficients.{} is not a number", file.string(), k));
    t.coefficients[k] = v.get<double>();
  }
  // The nonlinear parameters of hidden effects: hidden.TERM.PARAMETER_NAME.
  if (j.contains("hidden") && j["hidden"].is_object())
    for (const auto& [k, h] : j["hidden"].items()) {
      const fit::Term* term = fit::find_term(k);
      if (term == nullptr || !term->parameter || !h.is_object()) continue;
      const std::string key(term->parameter->name);
      if (h.contains(key) && h[key].is_number()) t.parameters[k] = h[key].get<double>();
    }
  return t;
}

std::map<std::string, double> coefficient_errors(const fit::ModelFit& fit, const Truth& truth) {
  std::map<std::string, double> out;
  auto add = [&](const std::string& name, double value) {
    const auto it = truth.coefficients.find(name);
    if (it == truth.coefficients.end() || it->second == 0.0) return;
    out[name] = (value - it->second) / std::abs(it->second);
  };
  add("1", fit.coefficients.intercept);
  for (std::size_t j = 0; j < fit.terms.size(); ++j) add(std::string(fit.terms[j]->name), fit.coefficients.b[j]);
  return out;
}

void add_truth(nlohmann::ordered_json& j, const fit::ModelFit& fit, const Truth& truth) {
  using Json = nlohmann::ordered_json;
  Json t;
  for (const auto& [k, v] : truth.coefficients) t[k] = v;
  j["truth"] = t;
  if (!truth.parameters.empty()) {
    Json p;
    for (const auto& [k, v] : truth.parameters) p[k] = {{std::string(fit::find_term(k)->parameter->name), v}};
    j["truth_parameters"] = p;
  }
  Json e;
  for (const auto& [k, v] : coefficient_errors(fit, truth)) e[k] = v;
  j["coefficient_error"] = e;
}

}  // namespace gyrotherm::studies
