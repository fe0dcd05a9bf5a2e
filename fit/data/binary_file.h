#pragma once
// Shared by the binary log readers (fit/data/autopilot_log.h), not a public
// header: a file read forward in blocks with the byte offset kept for
// messages, little-endian numbers of the C types both formats log, and what
// a reader holds while it reads (LogReader: the sensors of the kind read,
// their samples tallied and handed to the sink).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "fit/data/autopilot_log.h"

namespace gyrotherm::fit::binary {

// Reads a file forward in blocks: want(n) makes n bytes from the current
// offset readable at data() (fewer only at the end of the file), so a file
// of any size costs one block plus the longest message.
class BinaryFile {
 public:
  static constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

  // Throws InputError naming the file when it cannot be opened.
  explicit BinaryFile(const std::filesystem::path& file);

  // How many of the n bytes from offset() are readable at data().
  std::size_t want(std::size_t n);
  const std::uint8_t* data() const { return buffer_.data() + begin_; }
  // n no more than the last want() returned.
  void advance(std::size_t n) {
    begin_ += n;
    offset_ += n;
  }
  // Moves forward to `offset` (past the buffered bytes too).
  void seek_forward(std::uint64_t offset);
  std::uint64_t offset() const { return offset_; }
  const std::string& name() const { return name_; }

  // "FILE: byte N: message", the form of every error of these readers.
  [[noreturn]] void fail(std::uint64_t at_byte, const std::string& message) const;

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::string name_;
  std::unique_ptr<std::FILE, Closer> file_;
  std::vector<std::uint8_t> buffer_;
  std::size_t begin_ = 0, end_ = 0;
  std::uint64_t offset_ = 0;
  bool at_end_ = false;
};

// The C types the two formats log, as a number.
enum class Kind { i8, u8, i16, u16, i32, u32, i64, u64, f16, f32, f64 };

std::size_t size_of(Kind kind);

// An unsigned little-endian integer of `bytes` bytes (1, 2, 4 or 8).
inline std::uint64_t load_unsigned(const std::uint8_t* p, std::size_t bytes) {
  std::uint64_t u = 0;
  for (std::size_t i = 0; i < bytes; ++i) u |= std::uint64_t{p[i]} << (8 * i);
  return u;
}
inline std::uint16_t load_u16(const std::uint8_t* p) { return static_cast<std::uint16_t>(load_unsigned(p, 2)); }
inline std::uint32_t load_u32(const std::uint8_t* p) { return static_cast<std::uint32_t>(load_unsigned(p, 4)); }
inline std::uint64_t load_u64(const std::uint8_t* p) { return load_unsigned(p, 8); }

// The value of a field of that kind at p, as a double (an integer beyond 2⁵³
// rounded; IEEE half, single and double exactly).
double load_number(Kind kind, const std::uint8_t* p);

// Where a number the reader needs is in a message, and how to read it.
struct Field {
  std::size_t offset = 0;
  Kind kind = Kind::f32;
  double scale = 1.0;  // value = scale × the number stored
  bool present = false;
  double read(const std::uint8_t* payload) const { return scale * load_number(kind, payload + offset); }
};

// Text from a file, for a message: bytes outside printable ASCII as \xNN,
// cut after `max` characters with "...".
std::string printable(std::string_view text, std::size_t max = 80);
// "55 4c 6f 67": bytes as hex, for a message.
std::string hex_bytes(const std::uint8_t* p, std::size_t n);

// Counts a sample of a sensor into its summary.
void tally(LogSensor& sensor, double time_s, double temp_c);

// What a reader of either format holds during its one pass: the file, the
// kind read, the instance whose samples go to the sink (-1: none), and the
// contents so far.
class LogReader {
 public:
  LogReader(const std::filesystem::path& file, int instance, const SampleSink& sink, const SensorKind& kind)
      : in_(file), instance_(instance), sink_(sink) {
    contents_.kind = &kind;
  }

 protected:

  // The index in contents_.sensors of the sensor of `instance`, added
  // (logged as `message`) when it is not there yet.
  std::size_t sensor_of(int instance, std::string_view message);
  // One sample of `sensor` at time_s: its temperature (NaN when the format
  // has none) and axes read from `payload` (y and z NaN when not present),
  // tallied, and handed to the sink when it is the instance asked for.
  void take_sample(LogSensor& sensor, double time_s, const Field& temperature, const Field& x, const Field& y,
                   const Field& z, const std::uint8_t* payload);
  // One accelerometer sample (m/s²) of `instance`, tallied.
  void take_accel(int instance, double x, double y, double z);
  // A parameter the log records; the first value of each name is kept.
  void take_parameter(std::string name, double value) { contents_.parameters.emplace(std::move(name), value); }
  // The file ends inside the message starting at byte `at`.
  void truncate_at(std::uint64_t at) {
    contents_.truncated = true;
    contents_.truncated_at_byte = at;
  }
  // The contents, sensors sorted by instance.
  LogContents finish();

  BinaryFile in_;
  int instance_;
  const SampleSink& sink_;
  LogContents contents_;
};

// A reader's one pass: fills `contents` and hands the samples of `instance`
// (-1: none) to the sink.
using OnePass = std::function<LogContents(const std::filesystem::path& file, int instance, const SampleSink& sink)>;
// The public readers' contract on top of one pass: the default instance for
// a sink with instance -1 (two passes), and an instance not held refused.
LogContents read_choosing(const std::filesystem::path& file, int instance, const SampleSink& sink,
                          const OnePass& pass);
// read_choosing with the one pass of a Reader(file, instance, sink, kind).read().
template <class Reader>
LogContents read_with(const std::filesystem::path& file, int instance, const SampleSink& sink,
                      const SensorKind& kind) {
  return read_choosing(file, instance, sink, [&kind](const std::filesystem::path& f, int i, const SampleSink& s) {
    return Reader(f, i, s, kind).read();
  });
}

}  // namespace gyrotherm::fit::binary
