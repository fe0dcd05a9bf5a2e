// libFuzzer target: the ArduPilot DataFlash reader (fit/data/autopilot_log.h), through
// the body the two log readers' targets share (fuzz_support.h,
// read_autopilot_log): any InputError is the expected answer to a bad file;
// a file it reads must give, for each gyro it lists, exactly that many
// samples to a sink (a difference traps), and a description.

#include <cstdint>

#include "fit/data/autopilot_log.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto file = gyrotherm::fuzz::scratch_file("log.bin");
  return gyrotherm::fuzz::read_autopilot_log(file, gyrotherm::fit::read_dataflash, data, size);
}
