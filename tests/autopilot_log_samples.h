#pragma once
// What the reader tests (tests/ulog_test.cpp, tests/dataflash_test.cpp) take
// from a log through a reader of fit/data/autopilot_log.h: the samples it
// hands to its sink, compared to the bit (NaN equal to NaN in the time and
// the temperature), and the checks both make: of a large file, of a cut
// one, of one refused, and of the choice of a gyro.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "expect_input_error.h"
#include "fit/data/autopilot_log.h"

namespace gyrotherm::testing {

// One sample as the sink receives it.
struct LogSample {
  double time_s, temp_c, x, y, z;
  bool operator==(const LogSample& o) const {
    const auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
    return same(time_s, o.time_s) && same(temp_c, o.temp_c) && x == o.x && y == o.y && z == o.z;
  }
};
inline std::ostream& operator<<(std::ostream& os, const LogSample& s) {
  return os << "{" << s.time_s << ", " << s.temp_c << ", " << s.x << ", " << s.y << ", " << s.z << "}";
}

// A reader: fit::read_ulog or fit::read_dataflash.
using LogReaderFn = fit::AutopilotReader;
inline const fit::SensorKind& gyro_kind() { return fit::sensor_kinds().front(); }

// Every sample of gyro `instance` (-1: the default one) in file order, and
// the contents in *contents when it is given.
inline std::vector<LogSample> read_samples(LogReaderFn read, const std::filesystem::path& file, int instance,
                                           fit::LogContents* contents = nullptr) {
  std::vector<LogSample> out;
  const fit::LogContents c =
      read(file, instance, [&](double t, double tc, double x, double y, double z) { out.push_back({t, tc, x, y, z}); },
           gyro_kind());
  if (contents != nullptr) *contents = c;
  return out;
}

// A large file: gyro `instance` gives `n` samples, each equal to expected(k)
// (k counting from 0); compared as they come, not kept.
inline void expect_every_sample(LogReaderFn read, const std::filesystem::path& file, int instance, std::size_t n,
                                const std::function<LogSample(int k)>& expected) {
  std::size_t count = 0;
  bool all_equal = true;
  read(
      file, instance,
      [&](double t, double tc, double x, double y, double z) {
        all_equal = all_equal && LogSample{t, tc, x, y, z} == expected(static_cast<int>(count));
        ++count;
      },
      gyro_kind());
  EXPECT_EQ(count, n);
  EXPECT_TRUE(all_equal);
}

// A file that ends inside the message starting at byte `at` (a power cut):
// read up to there, gyro `instance` giving `samples` samples, the contents
// marked truncated at `at` and described so.
inline void expect_truncated_at(LogReaderFn read, const std::filesystem::path& file, int instance, std::uint64_t at,
                                std::size_t samples) {
  fit::LogContents c;
  EXPECT_EQ(read_samples(read, file, instance, &c).size(), samples);
  EXPECT_TRUE(c.truncated);
  EXPECT_EQ(c.truncated_at_byte, at);
  EXPECT_NE(c.describe().find("the file ends inside the message at byte " + std::to_string(at)), std::string::npos)
      << c.describe();
}

// `log` saved as `file` is refused by `read`: an InputError whose message
// holds every one of `words`.
template <class Writer>
void expect_refused(LogReaderFn read, const std::filesystem::path& file, const Writer& log,
                    const std::vector<std::string>& words) {
  log.save(file);
  expect_input_error([&] { read(file, -1, {}, gyro_kind()); }, words);
}

// The choice of a gyro, the same for both formats (fit/data/autopilot_log.h):
// in `with_gyros`, a log holding instances `held` ("0, 1 and 2"), the
// instance `absent` is refused naming the file and those held; in `without`,
// a log of that format holding no gyro, none is the default, the description
// ("`format`: no gyro samples") says so, and neither a sink without an
// instance nor instance 0 is read.
template <class Writer>
void expect_gyro_choice(LogReaderFn read, const std::filesystem::path& file, const Writer& with_gyros, int absent,
                        const std::string& held, const Writer& without, const std::string& format) {
  with_gyros.save(file);
  expect_input_error([&] { read_samples(read, file, absent); },
                     {file.filename().string(), "no gyro instance " + std::to_string(absent), "instances " + held});
  without.save(file);
  const fit::LogContents c = read(file, -1, {}, gyro_kind());
  EXPECT_EQ(c.default_instance(), -1);
  EXPECT_EQ(c.describe(), format + ": no gyro samples");
  expect_input_error([&] { read_samples(read, file, -1); },
                     {"none is chosen by default", format + ": no gyro samples"});
  expect_input_error([&] { read(file, 0, {}, gyro_kind()); }, {"no gyro instance 0", "it holds no gyro"});
}

}  // namespace gyrotherm::testing
