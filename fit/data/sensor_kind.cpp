// The sensor kinds (fit/data/sensor_kind.h): one entry each.
#include "fit/data/sensor_kind.h"

#include <fmt/format.h>

#include "fit/data/column_role.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

// The white noise's factor turns √q_w (base·√s) into the unit named, with
// √s = √h/60; the random walk's turns √q_r (base/√s) into base/√h: × 60.
//
// gyro: a rate in °/h. White noise: the angle random walk (°/√h = √q_w/60);
//   random walk: the rate random walk (°/h/√h).
// accel: a specific force in m/s² (gravity included: the bias the thermal
//   model fits sits on the constant the attitude gives). White noise: the
//   velocity random walk (m/s/√h = 60·√q_w); random walk: the acceleration
//   random walk (m/s²/√h); IEEE Std 1293 names them so.
// baro: a static pressure in Pa. In a chamber at constant pressure its
//   change with temperature is the sensor's offset; outside one, the weather
//   moves it too (a fit cannot tell the two apart). White noise as a density
//   (Pa·√s = √q_w); random walk in Pa/√h.
// mag: a magnetometer's flux density in gauss (PX4's unit). The field it
//   reads is the Earth's and the vehicle's as well as its own offset: a fit
//   sees the offset's change with temperature only where those hold still.
//   White noise as a density (gauss·√s); random walk in gauss/√h.
//
// The logs (ULog: PX4's msg/SensorGyro.msg, SensorAccel.msg, SensorBaro.msg,
// SensorMag.msg; DataFlash: ArduPilot's AP_InertialSensor/LogStructure.h IMU
// and AP_Baro/LogStructure.h BARO): PX4 logs pressure in Pa since v1.13
// (mbar before, which the ULog reader tells by the log's version); ArduPilot's
// MAG message has no temperature, so a DataFlash log's magnetometer cannot be
// fitted against one.
//
// The firmwares (PX4's src/modules/temperature_compensation: parameters
// temp_comp_params_{gyro,accel,baro,mag}.yaml, TC_M from v1.15; ArduPilot's
// AP_InertialSensor_tempcal.cpp, INS_TCALn_GYR* and _ACC*): PX4 corrects the
// barometer with a quintic in Pa, the others with cubics; ArduPilot has no
// polynomial for the barometer or the compass.
// clang-format off
const SensorKind kKinds[] = {
  {"gyro", "gyro", Quantity::gyro, "°/h", "gyro_dph", "gyr omega",
   {{{"arw", "deg/sqrt(h)", 1.0 / 60.0}, {"bias_instability", "deg/h", 1.0}, {"gauss_markov", "deg/h", 1.0}, {"rrw", "deg/h/sqrt(h)", 60.0}}}, true,
   {"sensor_gyro", "x y z", "rad/s"}, {"IMU IMU2 IMU3", "GyrX GyrY GyrZ", "rad/s"}, "gyro_x,gyro_y,gyro_z", "TC_G", 3, "GYR", "CAL_GYRO"},
  {"accel", "accelerometer", Quantity::accel, "m/s²", "accel_mps2", "acc",
   {{{"vrw", "m/s/sqrt(h)", 60.0}, {"bias_instability", "m/s^2", 1.0}, {"gauss_markov", "m/s^2", 1.0}, {"accel_random_walk", "m/s^2/sqrt(h)", 60.0}}}, false,
   {"sensor_accel", "x y z", "mps2"}, {"IMU IMU2 IMU3", "AccX AccY AccZ", "mps2"}, "accel_x,accel_y,accel_z", "TC_A", 3, "ACC", "CAL_ACC"},
  {"baro", "barometer", Quantity::pressure, "Pa", "baro_pa", "baro press",
   {{{"white_noise", "Pa*sqrt(s)", 1.0}, {"bias_instability", "Pa", 1.0}, {"gauss_markov", "Pa", 1.0}, {"pressure_random_walk", "Pa/sqrt(h)", 60.0}}}, false,
   {"sensor_baro", "pressure", "Pa"}, {"BARO BAR2 BAR3", "Press", "Pa"}, "pressure", "TC_B", 5, "", "CAL_BARO"},
  {"mag", "magnetometer", Quantity::magnetic, "gauss", "mag_gauss", "mag",
   {{{"white_noise", "gauss*sqrt(s)", 1.0}, {"bias_instability", "gauss", 1.0}, {"gauss_markov", "gauss", 1.0}, {"field_random_walk", "gauss/sqrt(h)", 60.0}}}, false,
   {"sensor_mag", "x y z", "gauss"}, {"", "", ""}, "mag_x,mag_y,mag_z", "TC_M", 3, "", "CAL_MAG"},
};
// clang-format on

}  // namespace

std::span<const SensorKind> sensor_kinds() { return kKinds; }

std::string sensor_kind_names() {
  std::string out;
  for (std::size_t k = 0; k < std::size(kKinds); ++k)
    out += std::string(k == 0 ? "" : k + 1 == std::size(kKinds) ? " or " : ", ") + std::string(kKinds[k].name);
  return out;
}

std::string shown_unit(std::string_view ascii) {
  static constexpr std::pair<std::string_view, std::string_view> kShown[] = {
      {"deg", "°"}, {"sqrt(h)", "√h"}, {"sqrt(s)", "√s"}, {"^2", "²"}, {"*", "·"}};
  std::string out(ascii);
  for (const auto& [from, to] : kShown)
    for (std::size_t at = out.find(from); at != std::string::npos; at = out.find(from, at + to.size()))
      out.replace(at, from.size(), to);
  return out;
}

std::vector<std::string_view> words_in(std::string_view list) {
  std::vector<std::string_view> words;
  while (!list.empty()) {
    const std::size_t space = list.find(' ');
    words.push_back(list.substr(0, space));
    list = space == std::string_view::npos ? std::string_view() : list.substr(space + 1);
  }
  return words;
}

bool names_sensor(std::string_view name, const SensorKind& kind) {
  bool named = false;
  const std::vector<std::string_view> prefixes = words_in(kind.words);
  for (const std::string& word : column_words(name)) {
    if (word.starts_with("temp")) return false;
    for (const std::string_view prefix : prefixes) named = named || word.starts_with(prefix);
  }
  return named;
}

const SensorKind& sensor_kind(std::string_view name) {
  if (name.empty()) return kKinds[0];
  for (const SensorKind& k : kKinds)
    if (k.name == name) return k;
  throw InputError(fmt::format("--sensor '{}': must be {}", name, sensor_kind_names()));
}

}  // namespace gyrotherm::fit
