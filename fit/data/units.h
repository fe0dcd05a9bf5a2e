#pragma once
// The units a log's columns may be written in: one table (fit/data/units.cpp),
// one line a unit. Every report, JSON and fit works in s, °C and the sensor's
// base unit (°/h for a gyro, m/s² for an accelerometer, Pa for a barometer); a
// column in another unit is converted as it is read (fit/data/measurement.h,
// Units), by the entry's factor, or for a temperature scale with an offset by
// its affine map. The command line's help, the error messages and the fit
// file's checks list the names from here.
//
// Adding a unit: one line in fit/data/units.cpp and its test in
// tests/units_test.cpp.

#include <span>
#include <string>
#include <string_view>

namespace gyrotherm::fit {

// gyro: a rate (°/h); accel: a specific force (m/s²); pressure: a
// barometer's (Pa); magnetic: a magnetometer's flux density (gauss, as PX4
// keeps it). The sensor kinds (fit/data/sensor_kind.h) name which one a
// record's measured channel is.
enum class Quantity { time, gyro, temperature, accel, pressure, magnetic };

struct Unit {
  Quantity quantity;
  std::string_view name;     // as --time-unit, --gyro-unit, --temp-unit take it and a fit saves it
  std::string_view meaning;  // "milliseconds"
  double factor = 1.0;                  // base = factor · value (s, °/h, °C, m/s², Pa)
  double (*affine)(double) = nullptr;   // instead, for a scale with an offset (K, °F)
  // How column names write it (fit/data/header_units.h): lower case, spaces
  // between, "°" written "deg" and "µ" "u" ("deg/s dps degps deg_s").
  std::string_view aliases = {};
  double to_base(double value) const { return affine ? affine(value) : value * factor; }
  bool is_base() const { return affine == nullptr && factor == 1.0; }
};

// Every unit, base units first within each quantity.
std::span<const Unit> unit_table();
// The unit of `quantity` named `name`; throws InputError naming `option`
// (e.g. "--gyro-unit") and the known names when there is none.
const Unit& find_unit(Quantity quantity, std::string_view name, std::string_view option);
// "s, ms, us": the names of a quantity's units, in table order; with `last`
// the final separator is that word ("s, ms or us").
std::string unit_names(Quantity quantity, std::string_view last = ", ");
// The base unit's name ("s", "dph", "C").
std::string_view base_unit(Quantity quantity);

}  // namespace gyrotherm::fit
