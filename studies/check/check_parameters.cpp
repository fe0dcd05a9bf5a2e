#include "studies/check/check_parameters.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "fit/data/measurement.h"
#include "sim/util/input_error.h"
#include "studies/export/firmware.h"

namespace gyrotherm::studies {

namespace {

constexpr int kPx4Instances = 4;       // TC_G0 .. TC_G3
constexpr int kArduPilotInstances = 5;  // INS_TCAL1_ .. INS5_TCAL_

std::vector<std::string> fields_of(std::string_view line) {
  std::vector<std::string> fields;
  std::string current;
  for (const char c : line) {
    if (c == ',' || c == ' ' || c == '\t') {
      if (!current.empty()) fields.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  if (!current.empty()) fields.push_back(current);
  return fields;
}

bool is_name(std::string_view s) {
  if (s.empty()) return false;
  for (const char c : s)
    if (!(std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
      return false;
  return true;
}

std::optional<double> number_of(std::string_view s) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

// One "name value" pair of a line, by the line's form; the form is the
// file's from its first parameter line on.
void read_line(const std::string& file, std::size_t line_no, std::string_view line, std::optional<bool>* qgc,
               std::map<std::string, double, std::less<>>* values) {
  const std::vector<std::string> f = fields_of(line);
  const bool five = f.size() == 5 && number_of(f[0]) && number_of(f[1]) && is_name(f[2]);
  const bool two = f.size() == 2 && is_name(f[0]);
  if (!five && !two)
    throw InputError(located(file, line_no,
                             fmt::format("expected a parameter line, 'NAME,VALUE' or 'NAME VALUE' (ArduPilot) or "
                                         "'VEHICLE COMPONENT NAME VALUE TYPE' (PX4, QGroundControl), found '{}'",
                                         std::string(line.substr(0, 80)))));
  if (qgc->has_value() && **qgc != five)
    throw InputError(located(file, line_no,
                             fmt::format("a {} line in a file whose first parameter line is {}", five ? "PX4" : "ArduPilot",
                                         five ? "ArduPilot's 'NAME VALUE'" : "PX4's five fields")));
  *qgc = five;
  const std::string& name = five ? f[2] : f[0];
  const std::string& text = five ? f[3] : f[1];
  const std::optional<double> value = number_of(text);
  if (!value)
    throw InputError(located(file, line_no, fmt::format("{}: '{}' is not a finite number", name, text)));
  const auto [at, added] = values->emplace(name, *value);
  if (!added && at->second != *value)
    throw InputError(located(file, line_no,
                             fmt::format("{} given again, as {} (before: {}); which one is meant?", name, *value,
                                         at->second)));
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

double required(const ParameterFile& p, const std::string& name, const std::string& why) {
  const std::optional<double> v = p.value(name);
  if (!v)
    throw InputError(fmt::format("{}: {} is missing ({}); a calibration needs its range and the coefficients of "
                                 "each axis it corrects",
                                 p.file, name, why));
  return *v;
}

std::optional<GyroCalibration> px4_calibration(const ParameterFile& p, int n) {
  const fit::SensorKind& kind = *p.kind;
  const std::string prefix = fmt::format("{}{}_", kind.px4_stem, n);
  bool any = false;
  for (const auto& [name, value] : p.values) any = any || starts_with(name, prefix);
  if (!any) return std::nullopt;
  GyroCalibration c;
  c.format = ParameterFormat::px4;
  c.instance = n;
  c.prefix = prefix;
  c.enable = p.value(fmt::format("{}_ENABLE", kind.px4_stem));
  c.tmin_c = required(p, prefix + "TMIN", "the lowest temperature");
  c.tmax_c = required(p, prefix + "TMAX", "the highest temperature");
  c.tref_c = static_cast<float>(required(p, prefix + "TREF", "the reference temperature"));
  if (const auto id = p.value(prefix + "ID")) c.device_id = static_cast<long long>(*id);
  // A one-axis sensor's coefficients have no axis suffix (TC_B0_X0).
  const auto name = [&](int k, std::size_t axis) {
    return kind.axes() == 1 ? fmt::format("{}X{}", prefix, k) : fmt::format("{}X{}_{}", prefix, k, axis);
  };
  for (std::size_t axis = 0; axis < kind.axes(); ++axis) {
    c.axes[axis] = p.value(name(0, axis)).has_value();
    if (!c.axes[axis]) continue;
    for (int k = 0; k <= kind.px4_order; ++k)
      c.px4_x[axis][static_cast<std::size_t>(k)] =
          static_cast<float>(required(p, name(k, axis), "a coefficient of an axis given"));
  }
  return c;
}

std::optional<GyroCalibration> ardupilot_calibration(const ParameterFile& p, int instance) {
  const std::string prefix = ardupilot_prefix(instance + 1);
  const std::string_view group = p.kind->ardupilot_group;
  bool any = false;
  for (const auto& [name, value] : p.values)
    any = any || (starts_with(name, prefix) && name.find(group) != std::string::npos);
  if (!any) return std::nullopt;
  GyroCalibration c;
  c.format = ParameterFormat::ardupilot;
  c.instance = instance;
  c.prefix = prefix;
  c.enable = p.value(prefix + "ENABLE");
  c.tmin_c = required(p, prefix + "TMIN", "the lowest temperature");
  c.tmax_c = required(p, prefix + "TMAX", "the highest temperature");
  c.tref_c = 35.0f;
  if (const auto id = p.value(ardupilot_gyro_id_name(instance, group))) c.device_id = static_cast<long long>(*id);
  static constexpr char kAxes[] = {'X', 'Y', 'Z'};
  for (int axis = 0; axis < 3; ++axis) {
    c.axes[axis] = p.value(fmt::format("{}{}1_{}", prefix, group, kAxes[axis])).has_value();
    if (!c.axes[axis]) continue;
    for (int k = 0; k < 3; ++k)
      c.ap_g[axis][k] = static_cast<float>(
          required(p, fmt::format("{}{}{}_{}", prefix, group, k + 1, kAxes[axis]), "a coefficient of an axis given"));
  }
  return c;
}

// Which kinds' thermal parameters `values` holds, for PX4 and for ArduPilot.
struct KindsHeld {
  std::vector<const fit::SensorKind*> px4, ardupilot;
};
KindsHeld kinds_held(const std::map<std::string, double, std::less<>>& values) {
  KindsHeld held;
  for (const fit::SensorKind& k : fit::sensor_kinds()) {
    bool px4 = false, ardupilot = false;
    for (const auto& [name, value] : values) {
      px4 = px4 || (starts_with(name, k.px4_stem) && name.size() > k.px4_stem.size() &&
                    (std::isdigit(static_cast<unsigned char>(name[k.px4_stem.size()])) != 0 ||
                     name[k.px4_stem.size()] == '_'));
      ardupilot = ardupilot || (!k.ardupilot_group.empty() &&
                                (starts_with(name, "INS_TCAL") || starts_with(name, "INS4_TCAL") ||
                                 starts_with(name, "INS5_TCAL")) &&
                                name.find(fmt::format("_{}", k.ardupilot_group)) != std::string::npos);
    }
    if (px4) held.px4.push_back(&k);
    if (ardupilot) held.ardupilot.push_back(&k);
  }
  return held;
}

}  // namespace

std::string ardupilot_gyro_id_name(int instance, std::string_view group) {
  if (instance == 0) return fmt::format("INS_{}_ID", group);
  if (instance < 3) return fmt::format("INS_{}{}_ID", group, instance + 1);
  return fmt::format("INS{}_{}_ID", instance + 1, group);
}

std::string_view parameter_format_name(ParameterFormat format) {
  static constexpr std::string_view kNames[] = {"px4", "ardupilot", "fit"};  // in the enum's order
  return kNames[static_cast<std::size_t>(format)];
}

std::optional<double> ParameterFile::value(std::string_view name) const {
  const auto it = values.find(name);
  if (it == values.end()) return std::nullopt;
  return it->second;
}

ParameterFile read_parameter_file(const std::string& file, std::string_view sensor) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the parameter file", file));
  std::stringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  ParameterFile p;
  p.file = file;
  if (const std::size_t first = all.find_first_not_of(" \t\r\n"); first != std::string::npos && all[first] == '{') {
    p.format = ParameterFormat::fit;
    p.fits = fit::load_fits(file, fit::FitKinds::any);
    p.kind = &p.fits.front().pipeline.columns.units.kind();
    if (!sensor.empty() && p.kind != &fit::sensor_kind(sensor))
      throw InputError(fmt::format("--sensor {}: {} is the {}'s fit (--sensor {})", sensor, file, p.kind->noun,
                                   p.kind->name));
    for (const fit::SavedFit& f : p.fits)
      if (p.fitted_sha256.empty() && !f.data_sha256.empty()) {
        p.fitted_file = f.data_file;
        p.fitted_sha256 = f.data_sha256;
      }
    return p;
  }
  std::optional<bool> qgc;
  std::istringstream lines(all);
  std::string line;
  bool in_caution = false;
  for (std::size_t line_no = 1; std::getline(lines, line); ++line_no) {
    const std::size_t hash = line.find('#');
    const std::string_view note =
        hash == std::string::npos ? std::string_view() : fit::trim(std::string_view(line).substr(hash + 1));
    const bool indented = hash != std::string::npos && line.compare(hash + 1, 3, "   ") == 0;
    if (note.starts_with("CAUTION"))
      p.cautions.emplace_back(note);
    else if (in_caution && indented && !note.empty())
      p.cautions.back() += fmt::format(" {}", note);
    in_caution = note.starts_with("CAUTION") || (in_caution && indented);
    if (const std::size_t sha = note.rfind(kFittedSha); note.starts_with(kFittedOn) && sha != std::string_view::npos) {
      p.fitted_file = std::string(note.substr(kFittedOn.size(), sha - kFittedOn.size()));
      p.fitted_sha256 = std::string(note.substr(sha + kFittedSha.size()));
    }
    if (hash != std::string::npos) line.erase(hash);
    const std::string_view trimmed = fit::trim(std::string_view(line).substr(0, line.find_last_not_of("\r") + 1));
    if (!trimmed.empty()) read_line(file, line_no, trimmed, &qgc, &p.values);
  }
  const KindsHeld held = kinds_held(p.values);
  std::vector<const fit::SensorKind*> any = held.px4;
  for (const fit::SensorKind* k : held.ardupilot)
    if (std::find(any.begin(), any.end(), k) == any.end()) any.push_back(k);
  // The kind: --sensor's; not given, the one the file holds (the gyro among several).
  p.kind = !sensor.empty() ? &fit::sensor_kind(sensor)
           : any.size() == 1 ? any.front()
                             : &fit::sensor_kinds().front();
  const bool px4 = std::find(held.px4.begin(), held.px4.end(), p.kind) != held.px4.end();
  const bool ardupilot = std::find(held.ardupilot.begin(), held.ardupilot.end(), p.kind) != held.ardupilot.end();
  if (px4 == ardupilot) {
    std::string others;
    for (const fit::SensorKind* k : any)
      others += fmt::format("{}the {}'s (--sensor {})", others.empty() ? "" : ", ", k->noun, k->name);
    const std::string ap = p.kind->ardupilot_group.empty()
                               ? std::string()
                               : fmt::format(" or ArduPilot's INS_TCAL{{n}}_{}{{k}}_{{axis}}", p.kind->ardupilot_group);
    throw InputError(fmt::format(
        "{}: {}; expected PX4's {}{{n}}_X{{k}}{}{} parameters (as `gyrotherm export` or the firmware's own "
        "calibration tools write them), or a fit file",
        file,
        px4 ? fmt::format("it holds both PX4 and ArduPilot {} thermal parameters", p.kind->noun)
            : fmt::format("it holds no {} thermal parameters{}", p.kind->noun,
                          others.empty() ? "" : fmt::format(" (it holds {})", others)),
        p.kind->px4_stem, p.kind->axes() == 1 ? "" : "_{axis}", ap));
  }
  p.format = px4 ? ParameterFormat::px4 : ParameterFormat::ardupilot;
  return p;
}

std::vector<GyroCalibration> gyro_calibrations(const ParameterFile& file) {
  std::vector<GyroCalibration> out;
  if (file.format == ParameterFormat::px4)
    for (int n = 0; n < kPx4Instances; ++n)
      if (auto c = px4_calibration(file, n)) out.push_back(*c);
  if (file.format == ParameterFormat::ardupilot)
    for (int n = 0; n < kArduPilotInstances; ++n)
      if (auto c = ardupilot_calibration(file, n)) out.push_back(*c);
  return out;
}

}  // namespace gyrotherm::studies
