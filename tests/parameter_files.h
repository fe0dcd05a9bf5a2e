#pragma once
// Parameter files as the firmwares load them, and each firmware's formula
// for what it subtracts, written here from its source for the tests:
//
// PX4: src/modules/temperature_compensation/TemperatureCompensation.cpp,
// calc_thermal_offsets_3D (float arithmetic, temperature clipped to
// [TMIN, TMAX], offset = x0 + x1 d + x2 d² + x3 d³, subtracted).
// ArduPilot: libraries/AP_InertialSensor/AP_InertialSensor_tempcal.cpp,
// TCal::polynomial_eval and correct_sensor (TEMP_REFERENCE 35, ×1e-6,
// v −= p(T − 35), v += p(T_cal − 35), both temperatures constrained).

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fit/data/prepare.h"

namespace gyrotherm::testing {

inline constexpr double kDphToRadS = 3.14159265358979323846 / (180.0 * 3600.0);

// name → value over the lines of a parameter file, passing over empty lines
// and '#' comments; split(line) gives a line's name and its value's text.
template <class Split>
std::map<std::string, float> read_parameters(const std::string& text, Split split) {
  std::map<std::string, float> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto [name, value] = split(line);
    out[name] = std::stof(value);
  }
  return out;
}

// name → value of a QGroundControl .params file (tab-separated: vehicle,
// component, name, value, type).
inline std::map<std::string, float> read_qgc(const std::string& text) {
  return read_parameters(text, [](const std::string& line) {
    std::istringstream f(line);
    std::string field[4];  // vehicle, component, name, value
    for (std::string& s : field) std::getline(f, s, '\t');
    return std::pair{field[2], field[3]};
  });
}

// name → value of a NAME,VALUE .param file.
inline std::map<std::string, float> read_ap(const std::string& text) {
  return read_parameters(text, [](const std::string& line) {
    const auto comma = line.find(',');
    return std::pair{line.substr(0, comma), line.substr(comma + 1)};
  });
}

// PX4's calc_thermal_offsets_3D (order 3; `suffix` "_0".."_2" the axis) or
// _1D (a barometer's: order 5, no suffix) of the parameters `stem` (TC_G0,
// TC_A0, TC_B0), in float as the firmware does: the temperature clipped to
// [TMIN, TMAX], offset = x0 + x1 d + x2 d² + ..., each power the last times d.
inline float px4_offset_of(const std::map<std::string, float>& p, const std::string& stem, const std::string& suffix,
                           int order, float temp) {
  const float tmax = p.at(stem + "_TMAX"), tmin = p.at(stem + "_TMIN"), tref = p.at(stem + "_TREF");
  float delta_temp;
  if (temp > tmax) delta_temp = tmax - tref;
  else if (temp < tmin) delta_temp = tmin - tref;
  else delta_temp = temp - tref;
  const auto x = [&](int k) { return p.at(stem + "_X" + std::to_string(k) + suffix); };
  float power = delta_temp, offset = x(0);
  for (int k = 1; k <= order; ++k, power *= delta_temp) offset += x(k) * power;
  return offset;
}

// The gyro's (TC_G0) for one axis.
inline float px4_offset(const std::map<std::string, float>& p, int axis, float temp) {
  return px4_offset_of(p, "TC_G0", "_" + std::to_string(axis), 3, temp);
}

// ArduPilot's correct_sensor for one axis: what it subtracts from the gyro
// (`group` GYR) or the accelerometer (ACC).
inline float ardupilot_subtracted(const std::map<std::string, float>& p, char axis, float temp, float cal_temp,
                                  const std::string& group = "GYR") {
  const float tmin = p.at("INS_TCAL1_TMIN"), tmax = p.at("INS_TCAL1_TMAX");
  const auto g = [&](int k) { return p.at("INS_TCAL1_" + group + std::to_string(k) + "_" + axis); };
  const auto poly = [&](float tdiff) { return (g(1) + (g(2) + g(3) * tdiff) * tdiff) * tdiff * 1.0e-6f; };
  temp = std::clamp(temp, tmin, tmax);
  cal_temp = std::clamp(cal_temp, tmin, tmax);
  return poly(temp - 35.0f) - poly(cal_temp - 35.0f);
}

// The instability (std of the 100 s window averages) of m's gyro less `subtracted_dph`.
inline double instability(const fit::Measurement& m, const std::vector<double>& subtracted_dph) {
  fit::Measurement rest = m;
  for (std::size_t i = 0; i < m.size(); ++i) rest.gyro_dph[i] -= subtracted_dph[i];
  const std::vector<double> w = fit::prepare_data(rest, {}).series.gyro_dph;
  double mean = 0.0, ss = 0.0;
  for (const double v : w) mean += v / static_cast<double>(w.size());
  for (const double v : w) ss += (v - mean) * (v - mean);
  return std::sqrt(ss / static_cast<double>(w.size() - 1));
}

// What PX4 subtracts from each sample of `m`, in its base unit, given the
// firmware's offset at a temperature (`offset`, in the firmware's unit, that
// many per base unit: `per_base`): the module runs once a second and
// publishes the offsets of the temperature it sees when that has moved more
// than 1 °C since the last published.
template <class Offset>
std::vector<double> px4_as_applied(const fit::Measurement& m, Offset offset, double per_base) {
  std::vector<double> applied(m.size());
  double held = 0.0, next_run = m.time_s[0];
  float last = -1e9f;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (m.time_s[i] >= next_run) {
      const auto temp = static_cast<float>(m.temp_c[i]);
      if (std::fabs(temp - last) > 1.0f) held = offset(last = temp) / per_base;
      while (next_run <= m.time_s[i]) next_run += 1.0;
    }
    applied[i] = held;
  }
  return applied;
}

// The gyro's (°/h), of axis `axis` of TC_G0.
inline std::vector<double> px4_as_applied(const fit::Measurement& m, const std::map<std::string, float>& p, int axis) {
  return px4_as_applied(m, [&](float t) { return px4_offset(p, axis, t); }, kDphToRadS);
}

}  // namespace gyrotherm::testing
