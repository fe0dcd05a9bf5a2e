// libFuzzer target: the measurement CSV reader, then the averaging and
// derivatives a fit runs on what it read.

#include <cstdint>

#include "fit/data/measurement.h"
#include "fit/pipeline.h"
#include "fuzz_support.h"
#include "sim/util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto file = gyrotherm::fuzz::scratch_file("data.csv");
  gyrotherm::fuzz::write_input(file, data, size);
  try {
    const gyrotherm::fit::Measurement m = gyrotherm::fit::read_measurement_csv(file);
    gyrotherm::fit::PipelineOptions options;
    options.averaging.window_s = 5.0;
    const gyrotherm::fit::PreparedData d = gyrotherm::fit::prepare_data(m, options);
    (void)d;
  } catch (const gyrotherm::InputError&) {
  }
  return 0;
}
