// libFuzzer target: the scenario, rig and gyro loaders on the same bytes, and
// the scenario-against-rig check.

#include <cstdint>

#include "fuzz_support.h"
#include "sim/config_loader.h"
#include "sim/util/input_error.h"
#include "sim/profile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto file = gyrotherm::fuzz::scratch_file("input.toml");
  gyrotherm::fuzz::write_input(file, data, size);
  using namespace gyrotherm::sim;
  try {
    const Scenario s = load_scenario(file);
    check_scenario_against_rig(s, RigConfig{}, "rig.toml");
    const Profile p(s.start_c, s.segments);
    (void)p.at(0.5 * p.duration_s());
  } catch (const gyrotherm::InputError&) {
  }
  try {
    (void)load_rig(file);
  } catch (const gyrotherm::InputError&) {
  }
  try {
    (void)load_gyro(file);
  } catch (const gyrotherm::InputError&) {
  }
  return 0;
}
