// ArduPilot DataFlash (.bin): the sensors of one kind, gyros and
// accelerometers in the IMU messages and barometers in BARO
// (fit/data/autopilot_log.h), written from ArduPilot's
// libraries/AP_Logger/LogStructure.h (FMT, the format characters),
// libraries/AP_InertialSensor/LogStructure.h (IMU) and
// libraries/AP_Baro/LogStructure.h (BARO). One pass: a table of the 256
// message types the FMT messages define; a read type's field offsets are
// worked out from its format and labels when its FMT is read.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <string_view>
#include <vector>

#include "fit/data/autopilot_log.h"
#include "fit/data/binary_file.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

namespace {

namespace fs = std::filesystem;
using binary::Field;
using binary::Kind;
using binary::printable;

constexpr std::uint8_t kSync1 = 0xA3, kSync2 = 0x95;
constexpr std::size_t kDataflashHeaderBytes = 3;  // A3 95 type
constexpr std::string_view kDataflashTitle = "DataFlash";
constexpr std::uint8_t kFmtType = 128;
// FMT: type (B), length (B), name (n, char[4]), format (N, char[16]), labels (Z, char[64]).
constexpr std::size_t kFmtBytes = kDataflashHeaderBytes + 1 + 1 + 4 + 16 + 64;

// One format character: its size, and how it reads as a number (none for text).
struct FormatChar {
  char c;
  std::size_t bytes;
  std::optional<Kind> kind;
  double scale;
};
constexpr FormatChar kFormatChars[] = {
    {'b', 1, Kind::i8, 1.0},   {'B', 1, Kind::u8, 1.0},    {'h', 2, Kind::i16, 1.0},   {'H', 2, Kind::u16, 1.0},
    {'i', 4, Kind::i32, 1.0},  {'I', 4, Kind::u32, 1.0},   {'f', 4, Kind::f32, 1.0},   {'d', 8, Kind::f64, 1.0},
    {'n', 4, std::nullopt, 1}, {'N', 16, std::nullopt, 1}, {'Z', 64, std::nullopt, 1}, {'c', 2, Kind::i16, 0.01},
    {'C', 2, Kind::u16, 0.01}, {'e', 4, Kind::i32, 0.01},  {'E', 4, Kind::u32, 0.01},  {'L', 4, Kind::i32, 1e-7},
    {'M', 1, Kind::u8, 1.0},   {'q', 8, Kind::i64, 1.0},   {'Q', 8, Kind::u64, 1.0},   {'a', 64, std::nullopt, 1},
    {'g', 2, Kind::f16, 1.0},
};
constexpr std::string_view kFormatCharList = "bBhHiIfdnNZcCeELMqQag";

const FormatChar* format_char(char c) {
  for (const FormatChar& f : kFormatChars)
    if (f.c == c) return &f;
  return nullptr;
}

// A fixed-size char field, up to its first NUL.
std::string text_field(const std::uint8_t* p, std::size_t bytes) {
  const char* s = reinterpret_cast<const char*>(p);
  return std::string(s, strnlen(s, bytes));
}

// Where a read message's fields are: the axes of the kind read (x alone for
// a barometer's Press) when it holds that kind, and an IMU's accelerometer
// (ax ay az, for the motion check) whatever the kind.
struct SensorLayout {
  Field time, instance, x, y, z, temperature, ax, ay, az;
  double time_units_per_s = 1e6;  // TimeUS; TimeMS (1e3) in older logs
  int fixed_instance = 0;         // IMU2 / BAR2 -> 1, IMU3 / BAR3 -> 2, IMU without I -> 0
  bool holds_kind = false;        // a message of the kind read (else an IMU read for its accelerometer)
};

// The position of `name` in a space-separated list, or -1.
int position_in(std::string_view list, std::string_view name) {
  const std::vector<std::string_view> words = words_in(list);
  const auto found = std::find(words.begin(), words.end(), name);
  return found == words.end() ? -1 : static_cast<int>(found - words.begin());
}

// Where a PARM message's name (N, 16 chars) and value are.
struct ParmLayout {
  std::size_t name_offset = 0;
  Field value;
};

struct MessageType {
  bool defined = false;
  std::size_t length = 0;  // of the whole message, header included
  std::string name;
  std::optional<SensorLayout> layout;
  std::optional<ParmLayout> parm;
};

std::vector<std::string> split_labels(const std::string& labels) {
  std::vector<std::string> columns;
  for (std::size_t begin = 0;;) {
    const std::size_t comma = labels.find(',', begin);
    columns.push_back(labels.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return columns;
}

// PARM's Name and Value by label (TimeUS,Name,Value[,Default]); none when
// the FMT does not have them as text of 16 and a number.
std::optional<ParmLayout> parm_layout(const std::string& format, const std::string& labels) {
  const std::vector<std::string> columns = split_labels(labels);
  if (columns.size() != format.size()) return std::nullopt;
  ParmLayout layout;
  bool named = false;
  std::size_t offset = 0;
  for (std::size_t i = 0; i < format.size(); ++i) {
    const FormatChar* f = format_char(format[i]);
    if (f == nullptr) return std::nullopt;
    if (columns[i] == "Name" && f->c == 'N') named = true, layout.name_offset = offset;
    if (columns[i] == "Value" && f->kind) layout.value = Field{offset, *f->kind, f->scale, true};
    offset += f->bytes;
  }
  if (!named || !layout.value.present) return std::nullopt;
  return layout;
}

class DataFlashReader : binary::LogReader {
 public:
  using LogReader::LogReader;

  LogContents read();

 private:
  void on_fmt(std::uint64_t at, const std::uint8_t* payload);
  SensorLayout sensor_layout(std::uint64_t at, const std::string& name, const std::string& format,
                             const std::string& labels, bool holds_kind) const;
  void on_sensor(std::uint64_t at, const SensorLayout& layout, const std::string& name, const std::uint8_t* payload);
  std::string defined_types() const;

  std::array<MessageType, 256> types_{};
};

LogContents DataFlashReader::read() {
  contents_.format = kDataflashTitle;
  const SensorKind& kind = *contents_.kind;
  contents_.unit = std::string(kind.dataflash.unit);
  if (kind.dataflash.messages.empty())
    in_.fail(0, fmt::format("--sensor {}: an ArduPilot log holds no {} temperature (its messages log none beside "
                            "the {}), so it cannot be fitted against one",
                            kind.name, kind.noun, kind.noun));
  for (;;) {
    const std::uint64_t at = in_.offset();
    const std::size_t head = in_.want(kDataflashHeaderBytes);
    if (head == 0) break;
    const std::uint8_t* p = in_.data();
    const bool sync = p[0] == kSync1 && (head < 2 || p[1] == kSync2);
    if (!sync) {
      const std::string found = head >= 2 ? fmt::format("{:02x} {:02x}", p[0], p[1]) : fmt::format("{:02x}", p[0]);
      if (at == 0) in_.fail(0, fmt::format("not a DataFlash log: expected a message starting a3 95, found {}", found));
      in_.fail(at, fmt::format("expected a message starting a3 95 after the previous one, found {} (a corrupt "
                               "log, or a message longer than its FMT says)",
                               found));
    }
    if (head < kDataflashHeaderBytes) {
      truncate_at(at);
      break;
    }
    const std::uint8_t type = p[2];
    const MessageType& known = types_[type];
    if (type != kFmtType && !known.defined)
      in_.fail(at, fmt::format("message type {} has no FMT message before it (a corrupt log; types defined: {})", type,
                               defined_types()));
    const std::size_t length = type == kFmtType ? kFmtBytes : known.length;
    if (in_.want(length) < length) {
      truncate_at(at);
      break;
    }
    const std::uint8_t* payload = in_.data() + kDataflashHeaderBytes;
    if (type == kFmtType)
      on_fmt(at, payload);
    else if (known.layout)
      on_sensor(at, *known.layout, known.name, payload);
    else if (known.parm)
      take_parameter(text_field(payload + known.parm->name_offset, 16), known.parm->value.read(payload));
    in_.advance(length);
  }
  return finish();
}

std::string DataFlashReader::defined_types() const {
  std::string out = fmt::format("{} FMT", kFmtType);
  for (std::size_t t = 0; t < types_.size(); ++t)
    if (types_[t].defined && t != kFmtType) out += fmt::format(", {} {}", t, printable(types_[t].name));
  return out.size() > 400 ? out.substr(0, 400) + "..." : out;
}

void DataFlashReader::on_fmt(std::uint64_t at, const std::uint8_t* payload) {
  const std::uint8_t type = payload[0];
  const std::size_t length = payload[1];
  const std::string name = text_field(payload + 2, 4);
  const std::string format = text_field(payload + 6, 16);
  const std::string labels = text_field(payload + 22, 64);
  const std::string what = fmt::format("FMT of type {} '{}' (format '{}')", type, printable(name), printable(format));
  if (length < kDataflashHeaderBytes) in_.fail(at, fmt::format("{}: length {}, less than the 3-byte header", what, length));
  if (type == kFmtType) {
    if (length != kFmtBytes || format != "BBnNZ")
      in_.fail(at, fmt::format("{}: length {}, expected FMT's own: {} bytes, format 'BBnNZ'", what, length, kFmtBytes));
    return;
  }
  // The length must be the format's, when every character is known (a
  // character this reader does not know only matters in a message it reads).
  std::size_t bytes = kDataflashHeaderBytes;
  bool all_known = true;
  for (const char c : format) {
    const FormatChar* f = format_char(c);
    all_known = all_known && f != nullptr;
    if (f != nullptr) bytes += f->bytes;
  }
  const bool holds_kind = position_in(contents_.kind->dataflash.messages, name) >= 0;
  const bool imu = position_in("IMU IMU2 IMU3", name) >= 0;
  if (all_known && bytes != length) {
    // A message this reader needs must be read right; any other is skipped
    // by the FMT's length, as pymavlink skips it, and said.
    if (holds_kind || imu)
      in_.fail(at,
               fmt::format("{}: the format adds up to {} bytes with the header, the FMT says {}", what, bytes, length));
    contents_.skipped_types.push_back({type, name, format, bytes, length});
  }
  MessageType& entry = types_[type];
  entry = MessageType{true, length, name, std::nullopt, std::nullopt};
  if (holds_kind || imu) entry.layout = sensor_layout(at, name, format, labels, holds_kind);
  if (name == "PARM" && bytes == length) entry.parm = parm_layout(format, labels);
}

SensorLayout DataFlashReader::sensor_layout(std::uint64_t at, const std::string& name, const std::string& format,
                                            const std::string& labels, bool holds_kind) const {
  const std::vector<std::string> columns = split_labels(labels);
  const std::string what =
      fmt::format("FMT of '{}' (format '{}', labels '{}')", name, printable(format), printable(labels));
  if (columns.size() != format.size())
    in_.fail(at, fmt::format("{}: {} labels for {} format characters", what, columns.size(), format.size()));
  const SensorKind::LogNaming& naming = contents_.kind->dataflash;
  SensorLayout layout;
  layout.holds_kind = holds_kind;
  layout.fixed_instance = std::max(0, position_in(holds_kind ? naming.messages : "IMU IMU2 IMU3", name));
  std::size_t offset = 0;
  Field time_ms;
  for (std::size_t i = 0; i < format.size(); ++i) {
    const FormatChar* f = format_char(format[i]);
    if (f == nullptr)
      in_.fail(at, fmt::format("{}: unknown format character '{}' (expected one of {})", what,
                               printable(std::string(1, format[i])), kFormatCharList));
    const std::string& label = columns[i];
    const int axis = holds_kind ? position_in(naming.fields, label) : -1;
    Field* const axes[] = {&layout.x, &layout.y, &layout.z};
    Field* slot = axis >= 0 && axis < 3              ? axes[axis]
                  : label == "TimeUS"                ? &layout.time
                  : label == "TimeMS"                ? &time_ms
                  : label == "I"                     ? &layout.instance
                  : label == "T" || label == "Temp"  ? &layout.temperature
                  : label == "AccX"                  ? &layout.ax
                  : label == "AccY"                  ? &layout.ay
                  : label == "AccZ"                  ? &layout.az
                                                     : nullptr;
    if (slot != nullptr) {
      if (!f->kind)
        in_.fail(at, fmt::format("{}: field '{}' is of format '{}', text, expected a number", what, label, f->c));
      *slot = Field{offset, *f->kind, f->scale, true};
    }
    offset += f->bytes;
  }
  if (!layout.time.present && time_ms.present) {
    layout.time = time_ms;
    layout.time_units_per_s = 1e3;
  }
  const std::vector<std::string_view> wanted = words_in(holds_kind ? naming.fields : std::string_view());
  const std::string expected = fmt::format("expected TimeUS or TimeMS{}{}", wanted.empty() ? "" : ", ",
                                           fmt::join(wanted, ", "));
  if (!layout.time.present) in_.fail(at, fmt::format("{}: no field 'TimeUS' ({})", what, expected));
  for (std::size_t axis = 0; axis < wanted.size(); ++axis)
    if (!(axis == 0 ? layout.x : axis == 1 ? layout.y : layout.z).present)
      in_.fail(at, fmt::format("{}: no field '{}' ({})", what, wanted[axis], expected));
  const std::string_view with_instance = naming.messages.substr(0, naming.messages.find(' '));
  if (layout.instance.present && holds_kind && name != with_instance)
    in_.fail(at, fmt::format("{}: an instance field 'I' in {}, expected only in {}", what, name, with_instance));
  return layout;
}

void DataFlashReader::on_sensor(std::uint64_t at, const SensorLayout& layout, const std::string& name,
                                const std::uint8_t* payload) {
  int instance = layout.fixed_instance;
  if (layout.instance.present) {
    const double value = layout.instance.read(payload);
    if (!(value >= 0.0 && value <= 255.0 && value == std::floor(value)))
      in_.fail(at, fmt::format("{} message: instance I = {}, expected a whole number 0..255", name, value));
    instance = static_cast<int>(value);
  }
  if (layout.holds_kind)
    take_sample(contents_.sensors[sensor_of(instance, name)], layout.time.read(payload) / layout.time_units_per_s,
                layout.temperature, layout.x, layout.y, layout.z, payload);
  if (layout.ax.present && layout.ay.present && layout.az.present)
    take_accel(instance, layout.ax.read(payload), layout.ay.read(payload), layout.az.read(payload));
}

}  // namespace

LogContents read_dataflash(const fs::path& file, int instance, const SampleSink& sink, const SensorKind& kind) {
  return binary::read_with<DataFlashReader>(file, instance, sink, kind);
}

// A message's two sync bytes begin the file.
LogFormat dataflash_log_format() { return {"dataflash", kDataflashTitle, "\xA3\x95", read_dataflash}; }

}  // namespace gyrotherm::fit
