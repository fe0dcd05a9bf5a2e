// libFuzzer target: the PX4 ULog reader (fit/data/autopilot_log.h). Any
// InputError is the expected answer to a bad file; a file it reads must give,
// for each gyro it lists, exactly that many samples to a sink (a difference
// traps), and a description.

#include <cstdint>

#include "fit/data/autopilot_log.h"
#include "fuzz_support.h"
#include "sim/util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto file = gyrotherm::fuzz::scratch_file("log.ulg");
  gyrotherm::fuzz::write_input(file, data, size);
  (void)gyrotherm::fit::autopilot_log_format(file);
  try {
    const gyrotherm::fit::LogContents contents = gyrotherm::fit::read_ulog(file);
    (void)contents.describe();
    for (const gyrotherm::fit::LogGyro& gyro : contents.gyros) {
      std::size_t samples = 0;
      gyrotherm::fit::read_ulog(file, gyro.instance, [&](double, double, double, double, double) { ++samples; });
      if (samples != gyro.samples) __builtin_trap();
    }
  } catch (const gyrotherm::InputError&) {
  }
  return 0;
}
