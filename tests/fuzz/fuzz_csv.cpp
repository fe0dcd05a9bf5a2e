// libFuzzer target: the measurement CSV reader, then the averaging and
// derivatives a fit runs on what it read; and the one-pass reader of large
// logs on the same file, which must agree: an input this short is within its
// prefix, so it must fail when the in-memory path fails and otherwise give
// the same windows to the bit (a difference traps).

#include <cstdint>

#include "fit/data/measurement.h"
#include "fit/data/streaming.h"
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
    const gyrotherm::fit::PreparedData s = gyrotherm::fit::prepare_data_streaming(file, options);
    if (s.series.time_s != d.series.time_s || s.series.gyro_dph != d.series.gyro_dph ||
        s.series.temp_c != d.series.temp_c || s.outliers.times_s != d.outliers.times_s ||
        s.averaging.bursts != d.averaging.bursts)
      __builtin_trap();
  } catch (const gyrotherm::InputError&) {
    // The one-pass reader must refuse it too.
    bool refused = false;
    try {
      gyrotherm::fit::PipelineOptions options;
      options.averaging.window_s = 5.0;
      (void)gyrotherm::fit::prepare_data_streaming(file, options);
    } catch (const gyrotherm::InputError&) {
      refused = true;
    }
    if (!refused) __builtin_trap();
  }
  return 0;
}
