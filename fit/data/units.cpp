#include "fit/data/units.h"

#include <fmt/format.h>

#include <vector>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

constexpr double kDegPerRad = 57.29577951308232;
constexpr double kStandardGravity = 9.80665;  // m/s² (CGPM 1901)

double from_kelvin(double k) { return k - 273.15; }
double from_fahrenheit(double f) { return (f - 32.0) * 5.0 / 9.0; }

using Q = Quantity;

// clang-format off
constexpr Unit kUnits[] = {
  {Q::time, "s", "seconds", 1.0, nullptr, "s sec secs second seconds"},
  {Q::time, "ms", "milliseconds", 1e-3, nullptr, "ms msec msecs millisecond milliseconds"},
  {Q::time, "us", "microseconds", 1e-6, nullptr, "us usec usecs microsecond microseconds"},
  {Q::time, "ns", "nanoseconds", 1e-9, nullptr, "ns nsec nsecs nanosecond nanoseconds"},
  {Q::time, "min", "minutes", 60.0, nullptr, "min mins minute minutes"},
  {Q::time, "h", "hours", 3600.0, nullptr, "h hr hrs hour hours"},
  {Q::gyro, "dph", "degrees per hour", 1.0, nullptr, "dph deg/h deg/hr degph deg_h deg/hour"},
  {Q::gyro, "dps", "degrees per second", 3600.0, nullptr, "dps deg/s deg/sec degps deg_s"},
  {Q::gyro, "rad/s", "radians per second", 3600.0 * kDegPerRad, nullptr, "rad/s rad/sec rads radps rad_s rps"},
  {Q::gyro, "mrad/s", "milliradians per second", 3.6 * kDegPerRad, nullptr, "mrad/s mrads mradps mrad_s"},
  {Q::gyro, "mdps", "millidegrees per second", 3.6, nullptr, "mdps mdeg/s mdeg_s"},
  {Q::gyro, "deg/min", "degrees per minute", 60.0, nullptr, "deg/min degpm deg_min dpm"},
  {Q::temperature, "C", "degrees Celsius", 1.0, nullptr, "c degc deg_c celsius"},
  {Q::temperature, "K", "kelvin", 1.0, &from_kelvin, "k kelvin"},
  {Q::temperature, "F", "degrees Fahrenheit", 1.0, &from_fahrenheit, "f degf deg_f fahrenheit"},
  {Q::accel, "mps2", "metres per second squared", 1.0, nullptr, "mps2 m/s^2 m/s2 m_s2 m/s/s ms2 mpss m_s_2"},
  {Q::accel, "g", "standard gravities (9.80665 m/s²)", kStandardGravity, nullptr, "g gee"},
  {Q::accel, "mg", "milli-g", 1e-3 * kStandardGravity, nullptr, "mg milli_g millig"},
  {Q::accel, "ug", "micro-g", 1e-6 * kStandardGravity, nullptr, "ug micro_g microg"},
  {Q::pressure, "Pa", "pascals", 1.0, nullptr, "pa pascal pascals"},
  {Q::pressure, "hPa", "hectopascals", 100.0, nullptr, "hpa hectopascal hectopascals"},
  {Q::pressure, "mbar", "millibars", 100.0, nullptr, "mbar millibar millibars mb"},
  {Q::pressure, "kPa", "kilopascals", 1000.0, nullptr, "kpa kilopascal kilopascals"},
  {Q::magnetic, "gauss", "gauss", 1.0, nullptr, "gauss ga g"},
  {Q::magnetic, "mgauss", "milligauss", 1e-3, nullptr, "mgauss milligauss mga mg"},
  {Q::magnetic, "T", "tesla (10⁴ gauss)", 1e4, nullptr, "t tesla"},
  {Q::magnetic, "mT", "millitesla", 10.0, nullptr, "mt millitesla"},
  {Q::magnetic, "uT", "microtesla", 1e-2, nullptr, "ut microtesla"},
  {Q::magnetic, "nT", "nanotesla", 1e-5, nullptr, "nt nanotesla"},
};
// clang-format on

}  // namespace

std::span<const Unit> unit_table() { return kUnits; }

const Unit& find_unit(Quantity quantity, std::string_view name, std::string_view option) {
  for (const Unit& u : kUnits)
    if (u.quantity == quantity && u.name == name) return u;
  throw InputError(fmt::format("{} {}: unknown unit (expected one of {})", option, name, unit_names(quantity)));
}

std::string unit_names(Quantity quantity, std::string_view last) {
  std::vector<std::string_view> names;
  for (const Unit& u : kUnits)
    if (u.quantity == quantity) names.push_back(u.name);
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k)
    out += std::string(k == 0 ? "" : k + 1 == names.size() ? last : ", ") + std::string(names[k]);
  return out;
}

std::string_view base_unit(Quantity quantity) {
  for (const Unit& u : kUnits)
    if (u.quantity == quantity && u.is_base()) return u.name;
  return {};
}

}  // namespace gyrotherm::fit
