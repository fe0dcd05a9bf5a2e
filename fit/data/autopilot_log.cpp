// What the two binary log readers share (fit/data/binary_file.h) and the
// summary of a log's sensors of one kind (fit/data/autopilot_log.h).

#include "fit/data/autopilot_log.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <system_error>

#include "fit/data/binary_file.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

namespace binary {

BinaryFile::BinaryFile(const std::filesystem::path& file)
    : name_(file.string()), file_(std::fopen(file.c_str(), "rb")) {
  if (!file_) throw InputError(located(name_, 0, fmt::format("cannot open: {}", std::strerror(errno))));
  // A block, or the whole file when it is smaller (want() grows it for a longer message).
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(file, error);
  buffer_.resize(error ? kBlockBytes : static_cast<std::size_t>(std::clamp<std::uintmax_t>(bytes, 4096, kBlockBytes)));
}

void BinaryFile::fail(std::uint64_t at_byte, const std::string& message) const {
  throw InputError(located(name_, 0, fmt::format("byte {}: {}", at_byte, message)));
}

std::size_t BinaryFile::want(std::size_t n) {
  while (end_ - begin_ < n && !at_end_) {
    if (begin_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    if (buffer_.size() < n) buffer_.resize(n);
    const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_.get());
    end_ += got;
    if (got == 0) {
      if (std::ferror(file_.get()) != 0) fail(offset_ + (end_ - begin_), "the file cannot be read further");
      at_end_ = true;
    }
  }
  return std::min(n, end_ - begin_);
}

void BinaryFile::seek_forward(std::uint64_t offset) {
  if (offset <= offset_) return;
  const std::uint64_t ahead = offset - offset_;
  if (ahead <= end_ - begin_) {
    advance(static_cast<std::size_t>(ahead));
    return;
  }
  if (offset > static_cast<std::uint64_t>(std::numeric_limits<long>::max()) ||
      std::fseek(file_.get(), static_cast<long>(offset), SEEK_SET) != 0)
    fail(offset_, fmt::format("cannot move to byte {}", offset));
  begin_ = end_ = 0;
  offset_ = offset;
  at_end_ = false;
}

std::size_t size_of(Kind kind) {
  static constexpr std::size_t kBytes[] = {1, 1, 2, 2, 4, 4, 8, 8, 2, 4, 8};  // in the order of Kind
  static_assert(std::size(kBytes) == static_cast<std::size_t>(Kind::f64) + 1);
  return kBytes[static_cast<std::size_t>(kind)];
}

namespace {
// IEEE 754 binary16: sign, 5 exponent bits (bias 15), 10 fraction bits.
double half_to_double(std::uint16_t h) {
  const int exponent = (h >> 10) & 0x1f;
  const double fraction = h & 0x3ff;
  double magnitude;
  if (exponent == 0)
    magnitude = std::ldexp(fraction, -24);
  else if (exponent == 31)
    magnitude = fraction == 0 ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
  else
    magnitude = std::ldexp(1024.0 + fraction, exponent - 25);
  return (h & 0x8000) != 0 ? -magnitude : magnitude;
}
}  // namespace

double load_number(Kind kind, const std::uint8_t* p) {
  switch (kind) {
    case Kind::i8:
      return static_cast<std::int8_t>(p[0]);
    case Kind::u8:
      return p[0];
    case Kind::i16:
      return static_cast<std::int16_t>(load_u16(p));
    case Kind::u16:
      return load_u16(p);
    case Kind::i32:
      return static_cast<std::int32_t>(load_u32(p));
    case Kind::u32:
      return load_u32(p);
    case Kind::i64:
      return static_cast<double>(static_cast<std::int64_t>(load_u64(p)));
    case Kind::u64:
      return static_cast<double>(load_u64(p));
    case Kind::f16:
      return half_to_double(load_u16(p));
    case Kind::f32:
      return std::bit_cast<float>(load_u32(p));
    case Kind::f64:
      return std::bit_cast<double>(load_u64(p));
  }
  return 0.0;
}

std::string printable(std::string_view text, std::size_t max) {
  std::string out;
  for (const char c : text.substr(0, max)) {
    const auto u = static_cast<unsigned char>(c);
    out += u >= 0x20 && u < 0x7f ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }
  return text.size() > max ? out + "..." : out;
}

std::string hex_bytes(const std::uint8_t* p, std::size_t n) {
  std::string out;
  for (std::size_t i = 0; i < n; ++i) out += fmt::format("{}{:02x}", i == 0 ? "" : " ", p[i]);
  return out;
}

void tally(LogSensor& sensor, double time_s, double temp_c) {
  if (sensor.samples == 0) sensor.first_time_s = time_s;
  sensor.last_time_s = time_s;
  ++sensor.samples;
  if (std::isfinite(temp_c)) {
    sensor.temp_min_c = sensor.samples_with_temperature == 0 ? temp_c : std::min(sensor.temp_min_c, temp_c);
    sensor.temp_max_c = sensor.samples_with_temperature == 0 ? temp_c : std::max(sensor.temp_max_c, temp_c);
    ++sensor.samples_with_temperature;
  }
}

std::size_t LogReader::sensor_of(int instance, std::string_view message) {
  std::vector<LogSensor>& sensors = contents_.sensors;
  const auto same = std::find_if(sensors.begin(), sensors.end(), [&](const LogSensor& g) { return g.instance == instance; });
  if (same != sensors.end()) return static_cast<std::size_t>(same - sensors.begin());
  LogSensor added;
  added.instance = instance;
  added.message = std::string(message);
  sensors.push_back(added);
  return sensors.size() - 1;
}

void LogReader::take_sample(LogSensor& sensor, double time_s, const Field& temperature, const Field& x, const Field& y,
                            const Field& z, const std::uint8_t* payload) {
  const double temp_c = temperature.present ? temperature.read(payload) : NAN;
  tally(sensor, time_s, temp_c);
  if (sink_ && sensor.instance == instance_)
    sink_(time_s, temp_c, x.read(payload), y.present ? y.read(payload) : NAN, z.present ? z.read(payload) : NAN);
}

void LogReader::take_accel(int instance, double x, double y, double z) {
  std::vector<LogAccel>& accels = contents_.accels;
  auto a = std::find_if(accels.begin(), accels.end(), [&](const LogAccel& e) { return e.instance == instance; });
  if (a == accels.end()) {
    accels.push_back(LogAccel{});
    a = accels.end() - 1;
    a->instance = instance;
  }
  const double norm = std::sqrt(x * x + y * y + z * z);
  if (!std::isfinite(norm)) return;
  if (a->samples == 0) a->first[0] = x, a->first[1] = y, a->first[2] = z;
  ++a->samples;
  const double first = std::sqrt(a->first[0] * a->first[0] + a->first[1] * a->first[1] + a->first[2] * a->first[2]);
  const double cosine = first > 0.0 && norm > 0.0 ? (x * a->first[0] + y * a->first[1] + z * a->first[2]) / (first * norm) : 1.0;
  const double tilt = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
  const double magnitude_error = std::abs(norm - kStandardGravity);
  a->largest_tilt_deg = std::max(a->largest_tilt_deg, tilt);
  a->largest_magnitude_error = std::max(a->largest_magnitude_error, magnitude_error);
  if (tilt > kAccelTiltLimitDeg || magnitude_error > kAccelMagnitudeLimit) ++a->moving;
}

LogContents LogReader::finish() {
  std::stable_sort(contents_.sensors.begin(), contents_.sensors.end(),
                   [](const LogSensor& a, const LogSensor& b) { return a.instance < b.instance; });
  std::stable_sort(contents_.accels.begin(), contents_.accels.end(),
                   [](const LogAccel& a, const LogAccel& b) { return a.instance < b.instance; });
  return std::move(contents_);
}

LogContents read_choosing(const std::filesystem::path& file, int instance, const SampleSink& sink,
                          const OnePass& pass) {
  if (sink && instance < 0) {
    const LogContents contents = pass(file, -1, {});
    instance = contents.default_instance();
    if (instance < 0)
      throw InputError(located(file.string(), 0,
                               fmt::format("no {} has 2 samples with a temperature, so none is chosen by "
                                           "default; the file holds: {}",
                                           contents.kind->noun, contents.describe())));
  }
  LogContents contents = pass(file, instance, sink);
  if (instance >= 0 && std::none_of(contents.sensors.begin(), contents.sensors.end(),
                                    [&](const LogSensor& g) { return g.instance == instance; }))
    throw InputError(located(file.string(), 0,
                             contents.sensors.empty()
                                 ? fmt::format("no {0} instance {1} in the file; it holds no {0}",
                                               contents.kind->noun, instance)
                                 : fmt::format("no {} instance {} in the file; it holds instance{} {}",
                                               contents.kind->noun, instance, contents.sensors.size() == 1 ? "" : "s",
                                               contents.instances())));
  return contents;
}

}  // namespace binary

std::string LogContents::instances() const {
  if (sensors.empty()) return "none";
  std::string out;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (i > 0) out += i + 1 == sensors.size() ? " and " : ", ";
    out += std::to_string(sensors[i].instance);
  }
  return out;
}

const LogAccel* LogContents::accel(int instance) const {
  for (const LogAccel& a : accels)
    if (a.instance == instance) return &a;
  return nullptr;
}

std::string LogContents::describe() const {
  std::string out = format + ":";
  if (sensors.empty()) out += fmt::format(" no {} samples", kind == nullptr ? "gyro" : kind->noun);
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const LogSensor& g = sensors[i];
    out += fmt::format("{} {} instance {}", i == 0 ? "" : ";", g.message, g.instance);
    if (g.device_id != 0) out += fmt::format(" (device {})", g.device_id);
    out += fmt::format(": {} sample{}", g.samples, g.samples == 1 ? "" : "s");
    if (g.samples > 0) out += fmt::format(", {:.3f}..{:.3f} s", g.first_time_s, g.last_time_s);
    if (g.samples_with_temperature == 0)
      out += ", temperature NaN throughout";
    else
      out += fmt::format(", {:.2f}..{:.2f} °C", g.temp_min_c, g.temp_max_c);
    if (g.samples_with_temperature > 0 && g.samples_with_temperature < g.samples)
      out += fmt::format(" ({} of {} samples with a temperature)", g.samples_with_temperature, g.samples);
  }
  if (!unit_from.empty()) out += fmt::format("; read in {} ({})", unit, unit_from);
  if (truncated)
    out += fmt::format("; the file ends inside the message at byte {} (a power cut?): read up to there",
                       truncated_at_byte);
  for (const SkippedType& s : skipped_types)
    out += fmt::format("; skipped (not read): FMT of type {} '{}' (format '{}'): the format adds up to {} bytes with "
                       "the header, the FMT says {} (its messages skipped by the FMT's length)",
                       s.type, binary::printable(s.name), binary::printable(s.format), s.format_bytes, s.fmt_length);
  return out;
}

int LogContents::default_instance() const {
  for (const LogSensor& g : sensors)
    if (g.samples_with_temperature >= 2) return g.instance;
  return -1;
}

const std::vector<LogFormat>& log_format_registry() {
  static const std::vector<LogFormat> formats = {
#define LOG_FORMAT(name) name##_log_format(),
#include "fit/data/log_formats.def"
#undef LOG_FORMAT
  };
  return formats;
}

const LogFormat* log_format_of(const std::filesystem::path& file) {
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (f == nullptr) return nullptr;
  std::array<char, 16> head{};
  const std::size_t got = std::fread(head.data(), 1, head.size(), f);
  std::fclose(f);
  const std::string_view start(head.data(), got);
  for (const LogFormat& format : log_format_registry())
    if (start.starts_with(format.magic)) return &format;
  return nullptr;
}

std::string autopilot_log_format(const std::filesystem::path& file) {
  const LogFormat* format = log_format_of(file);
  return format == nullptr ? std::string() : std::string(format->name);
}

bool stated_by_log_format(std::string_view source) {
  return std::any_of(log_format_registry().begin(), log_format_registry().end(),
                     [&](const LogFormat& f) { return source.starts_with(f.title); });
}

}  // namespace gyrotherm::fit
