#pragma once
// A scenario (scenarios/*.toml): the temperature profile, the sample rate, the
// room, the initial condition, the seed, and which rig and gyro files to use.
//
// The optional [spread] table is for Monte Carlo campaigns (`gyrotherm score`,
// studies/score/campaign.h): relative half-widths r of gyro parameters, 0 <= r < 1. Each
// trial draws the parameter p = p0·(1 + r·u), u uniform in [−1, 1], from the
// trial's seed; `gyrotherm simulate` ignores the table.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "sim/profile.h"

namespace gyrotherm::sim {

enum class InitialCondition {
  soaked,  // every node at start_c; the gyro is switched on at t = 0
  steady,  // thermal equilibrium at start_c with the gyro already running
};

// The keys of [spread]: the gyro file's keys of the true coefficients
// ([truth]) and of the noise levels ([noise]), in the order trials draw them.
inline constexpr std::array<std::string_view, 10> kSpreadKeys{
    "b0_dph", "b1_dph_per_c", "b2_dph_per_c2", "b3_dph_per_c_per_s",            // [truth]
    "arw_deg_per_sqrt_h", "bias_instability_dph", "rrw_dph_per_sqrt_h",        // [noise]
    "quantization_arcsec", "glitch_rate_per_h", "glitch_size_dph"};

struct Scenario {
  std::string name;
  std::string description;
  std::filesystem::path file;       // where it was read from (empty if built in code)
  std::filesystem::path rig_file;   // resolved relative to the scenario file
  std::filesystem::path gyro_file;
  std::uint64_t seed = 1;
  double sample_rate_hz = 1.0;
  double room_c = 23.0;
  bool chamber = true;              // false: no chamber, the INS sits in the room
  double start_c = 23.0;            // first set point, and the soak temperature
  InitialCondition initial = InitialCondition::soaked;
  std::vector<Segment> segments;
  std::map<std::string, double> spread;  // [spread]: key of kSpreadKeys → r; absent = fixed
};

}  // namespace gyrotherm::sim
