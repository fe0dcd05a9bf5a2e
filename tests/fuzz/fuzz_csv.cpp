// libFuzzer target: the measurement CSV reader, then the averaging and
// derivatives a fit runs on what it read; and the one-pass reader of large
// logs on the same file, which must agree: an input this short is within its
// prefix, so it must fail when the in-memory path fails and otherwise give
// the same windows to the bit (a difference traps).
// An input may start with one byte 0x01..0x07 that no CSV holds, choosing
// the reading's form (fit/data/csv_dialect.h): bit 0 the decimal comma,
// bit 1 a sample rate instead of a time column, bit 2 the delimiter given as
// a semicolon instead of read from the header.

#include <cstdint>

#include "fit/data/measurement.h"
#include "fit/data/streaming.h"
#include "fit/data/prepare.h"
#include "fuzz_support.h"
#include "sim/util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto file = gyrotherm::fuzz::scratch_file("data.csv");
  gyrotherm::fit::PipelineOptions options;
  options.averaging.window_s = 5.0;
  if (size > 0 && data[0] >= 1 && data[0] <= 7) {
    options.columns.csv.decimal_comma = (data[0] & 1) != 0;
    options.columns.csv.rate_hz = (data[0] & 2) != 0 ? 4.0 : 0.0;
    options.columns.csv.delimiter = (data[0] & 4) != 0 ? "semicolon" : "auto";
    ++data;
    --size;
  }
  gyrotherm::fuzz::write_input(file, data, size);
  try {
    const gyrotherm::fit::Measurement m = gyrotherm::fit::read_measurement_csv(file, options.columns);
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
      (void)gyrotherm::fit::prepare_data_streaming(file, options);
    } catch (const gyrotherm::InputError&) {
      refused = true;
    }
    if (!refused) __builtin_trap();
  }
  return 0;
}
