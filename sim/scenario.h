#pragma once
// A scenario (scenarios/*.toml): the temperature profile, the sample rate, the
// room, the initial condition, the seed, and which rig and gyro files to use.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/profile.h"

namespace gyrotherm::sim {

enum class InitialCondition {
  soaked,  // every node at start_c; the gyro is switched on at t = 0
  steady,  // thermal equilibrium at start_c with the gyro already running
};

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
};

}  // namespace gyrotherm::sim
