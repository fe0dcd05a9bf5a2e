#pragma once
// Reading scenario, rig and gyro files (TOML). Every key is checked: an
// unknown key, a value of the wrong type, a non-finite number or a value that
// breaks its rule (a negative capacity, a zero ramp rate, a set point outside
// the chamber's range) throws InputError naming the file, the line and the key,
// and what was expected. Keys that are absent take the documented defaults of
// sim/rig_config.h and sim/gyro_config.h. Paths inside a scenario are relative
// to the scenario file.

#include <filesystem>
#include <string_view>

#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/scenario.h"

namespace gyrotherm::sim {

Scenario load_scenario(const std::filesystem::path& file);
RigConfig load_rig(const std::filesystem::path& file);
GyroConfig load_gyro(const std::filesystem::path& file);

// Checks what needs both files: the start temperature and every set point lie
// within the chamber's working range.
void check_scenario_against_rig(const Scenario& scenario, const RigConfig& rig,
                                const std::filesystem::path& rig_file);

// Applies "TERM=COEF" (the --hidden option): TERM must be a hidden-effect term.
void apply_hidden_option(GyroConfig& gyro, std::string_view term_equals_coefficient);

}  // namespace gyrotherm::sim
