#pragma once
// Writing gyro, rig and scenario files (TOML) that sim/config_loader.h reads
// back to the same values, e.g. the files `gyrotherm plan` writes beside the
// test it designs (keys and tables: docs/contracts.md, "Scenario, rig and gyro
// files").
//
// Every number is written in the shortest form that parses back to the same
// double (fmt's "{}", with ".0" added to a whole number so that it stays a
// TOML float); every key the loader knows is written, so nothing falls back
// to a default that may differ from the value given. A scenario's durations
// are written in seconds (duration_s) and its rig and gyro files as given
// (relative paths are resolved from the scenario file's folder on reading).
// Not written: the scenario's `file` and each segment's `source_line` (where
// they were read from), and a gyro's coefficients of names outside the effect
// registry.
//
// The gyro's [hidden] table is written when the gyro holds a coefficient of a
// hidden effect or a parameter of an effect (as one read from a file with a
// [hidden] table does), and then with every hidden coefficient and every
// parameter: the loader fills both maps in whenever the table is there, so the
// maps read back are those written from, not only the values they give.
//
// Written here rather than by toml++ (which reads every file back): toml++ 3.3,
// Debian 12's, writes a double with 17 digits (0.1 as 0.10000000000000001),
// orders a table's keys alphabetically and writes no comments, so the files
// would lose their units and their order; tests/config_writer_test.cpp parses
// what this writes with toml++ and compares every value.
//
// `header`: what wrote the file and why, one or more lines, each written as a
// '#' comment at the top.

#include <string>
#include <string_view>

#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/scenario.h"

namespace gyrotherm::sim {

std::string gyro_toml(const GyroConfig& gyro, std::string_view header);
std::string rig_toml(const RigConfig& rig, std::string_view header);
// rig_file, gyro_file: the scenario's `rig` and `gyro` keys. Throws InputError
// for a seed above 2⁶³ − 1 (a TOML integer is signed 64-bit).
std::string scenario_toml(const Scenario& scenario, std::string_view rig_file, std::string_view gyro_file,
                          std::string_view header);

}  // namespace gyrotherm::sim
