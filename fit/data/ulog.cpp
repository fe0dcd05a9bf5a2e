// PX4 ULog: the sensors of one kind, the instances of its topic
// (`sensor_gyro`, `sensor_accel`, ...; fit/data/autopilot_log.h), written
// from PX4-Autopilot's docs/en/dev_log/ulog_file_format.md. One pass: the
// format definitions are kept as parsed field lists (a few hundred in a PX4
// log); a format's size and a field's offset are worked out when a topic is
// subscribed, since the spec lets a type be used before it is defined.

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "fit/data/autopilot_log.h"
#include "fit/data/binary_file.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

namespace {

namespace fs = std::filesystem;
using binary::Field;
using binary::hex_bytes;
using binary::Kind;
using binary::printable;

constexpr std::size_t kFileHeaderBytes = 16;
constexpr std::string_view kULogTitle = "ULog";
constexpr std::string_view kULogMagic("ULog\x01\x12\x35", 7);
constexpr std::size_t kUlogMessageHeaderBytes = 3;  // uint16 size, uint8 type
constexpr std::string_view kAccelTopic = "sensor_accel";
// PX4 logs sensor_baro.pressure in Pa from v1.13 on (pull request 19284,
// "sensor_baro.msg use SI"), in mbar before.
constexpr int kPascalsFromMinor = 13;
// A largest pressure above this is in Pa (an atmosphere is 1e5 Pa, 1e3
// mbar; 2000 mbar is more than any weather); without the version, one from
// 300 up to it is an atmosphere in mbar (below, a vacuum: either unit).
constexpr double kLargestMillibars = 2000.0;
constexpr double kSmallestMillibarAtmosphere = 300.0;
// Deeper nesting than any PX4 message (about 3 levels) means a broken file,
// and bounds the recursion on one.
constexpr int kMaxNesting = 32;
constexpr std::size_t kMaxFormatBytes = std::size_t{1} << 24;

struct BasicType {
  std::string_view name;
  Kind kind;
};
constexpr BasicType kBasicTypes[] = {
    {"int8_t", Kind::i8},   {"uint8_t", Kind::u8},   {"int16_t", Kind::i16}, {"uint16_t", Kind::u16},
    {"int32_t", Kind::i32}, {"uint32_t", Kind::u32}, {"int64_t", Kind::i64}, {"uint64_t", Kind::u64},
    {"float", Kind::f32},   {"double", Kind::f64},   {"bool", Kind::u8},     {"char", Kind::i8},
};
constexpr std::string_view kBasicTypeList =
    "int8_t, uint8_t, int16_t, uint16_t, int32_t, uint32_t, int64_t, uint64_t, float, double, bool, char";

const BasicType* basic_type(std::string_view name) {
  for (const BasicType& t : kBasicTypes)
    if (t.name == name) return &t;
  return nullptr;
}

// "type name" or "type[count] name" of a format definition.
struct FieldDef {
  std::string type, name;
  std::size_t count = 1;
  bool array = false;
};

struct FormatDef {
  std::uint64_t at_byte = 0;  // of its 'F' message
  std::vector<FieldDef> fields;
};

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\0')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.remove_suffix(1);
  return s;
}

// Where a sensor topic's fields are in a data message of one subscription:
// the axes (x y z, or one: pressure as x), its temperature and device id.
struct SensorLayout {
  Field timestamp, x, y, z, temperature, device_id;
  std::size_t needed_bytes = 0;  // the end of the last field read
};

struct Subscription {
  int sensor = -1;  // index into LogContents::sensors, -1 for another topic
  int accel = -1;   // sensor_accel's multi_id, -1 for another topic
  SensorLayout accel_layout;  // sensor_accel's timestamp, x, y, z
};

class ULogReader : binary::LogReader {
 public:
  using LogReader::LogReader;

  LogContents read();

 private:
  void read_header();
  void on_flag_bits(std::uint64_t at, const std::uint8_t* p, std::size_t size);
  void on_format(std::uint64_t at, const std::uint8_t* p, std::size_t size);
  void on_subscription(std::uint64_t at, const std::uint8_t* p, std::size_t size);
  void on_unsubscription(std::uint64_t at, const std::uint8_t* p, std::size_t size);
  void on_data(std::uint64_t at, const std::uint8_t* p, std::size_t size);
  void on_parameter(std::uint64_t at, const std::uint8_t* p, std::size_t size);
  void on_information(std::uint64_t at, const std::uint8_t* p, std::size_t size);
  void settle_unit();
  std::size_t size_of_type(const std::string& type, const std::string& within, int depth);
  std::size_t size_of_format(const std::string& name, int depth);
  // The fields `axes` ("x y z", "pressure") of format `name`. `required`: a
  // format without them (or with one not a number) is an error; else
  // (sensor_accel, read only for a motion check) the fields it lacks are
  // left not present.
  SensorLayout sensor_layout(const std::string& name, std::string_view axes, std::uint64_t subscribed_at,
                             bool required = true);

  std::map<std::string, FormatDef, std::less<>> formats_;
  std::unordered_map<std::string, std::size_t> format_bytes_;  // sizes worked out so far
  std::unordered_map<std::uint16_t, Subscription> subscriptions_;
  std::vector<SensorLayout> layouts_;            // of each sensor's format, by index in contents_.sensors
  std::vector<std::uint64_t> appended_offsets_;  // where appended data starts, ascending
  int version_major_ = -1, version_minor_ = -1;  // ver_sw_release, when the log has it
  double largest_value_ = 0.0;                   // |x| of the kind read, over its samples
};

LogContents ULogReader::read() {
  read_header();
  for (;;) {
    const std::uint64_t at = in_.offset();
    // Data appended after a message cut short (flag bits, DATA_APPENDED): the
    // cut message is dropped and reading goes on where the appended data starts.
    while (!appended_offsets_.empty() && appended_offsets_.front() <= at)
      appended_offsets_.erase(appended_offsets_.begin());
    const std::size_t head = in_.want(kUlogMessageHeaderBytes);
    if (head == 0) break;
    std::size_t size = 0;
    if (head == kUlogMessageHeaderBytes) size = binary::load_u16(in_.data());
    const std::size_t whole = kUlogMessageHeaderBytes + size;
    if (!appended_offsets_.empty() &&
        at + (head < kUlogMessageHeaderBytes ? kUlogMessageHeaderBytes : whole) > appended_offsets_.front()) {
      in_.seek_forward(appended_offsets_.front());
      continue;
    }
    if (head < kUlogMessageHeaderBytes || in_.want(whole) < whole) {
      truncate_at(at);
      break;
    }
    // The types read; information, default parameters, strings, sync, dropouts and
    // unknown types are passed over (the spec).
    using Handler = void (ULogReader::*)(std::uint64_t, const std::uint8_t*, std::size_t);
    static constexpr std::pair<char, Handler> kHandlers[] = {{'B', &ULogReader::on_flag_bits},
                                                             {'F', &ULogReader::on_format},
                                                             {'A', &ULogReader::on_subscription},
                                                             {'R', &ULogReader::on_unsubscription},
                                                             {'D', &ULogReader::on_data},
                                                             {'P', &ULogReader::on_parameter},
                                                             {'I', &ULogReader::on_information}};
    const char type = static_cast<char>(in_.data()[2]);
    for (const auto& [handled, handler] : kHandlers)
      if (type == handled) (this->*handler)(at, in_.data() + kUlogMessageHeaderBytes, size);
    in_.advance(whole);
  }
  settle_unit();
  return finish();
}

void ULogReader::settle_unit() {
  const SensorKind& kind = *contents_.kind;
  contents_.unit = std::string(kind.ulog.unit);
  if (kind.quantity != Quantity::pressure || contents_.sensors.empty()) return;
  // The values first: no weather gives 2000 mbar, so a larger pressure is in
  // Pa whatever the version says (a build without tags logs v0.0; a v1.13
  // development build may predate the change).
  const bool version_known = version_major_ >= 1;
  const std::string version = fmt::format("v{}.{}", version_major_, version_minor_);
  if (largest_value_ > kLargestMillibars) {
    contents_.unit = "Pa";
    const bool version_says_mbar = version_known && version_major_ == 1 && version_minor_ < kPascalsFromMinor;
    contents_.unit_from = fmt::format(
        "its largest pressure, {:g}, is above {:g}, so Pa{}", largest_value_, kLargestMillibars,
        !version_known      ? std::string()
        : version_says_mbar ? fmt::format(" (though its ver_sw_release, {}, is from before PX4 logged Pa)", version)
                            : fmt::format(", as its ver_sw_release, {}, says", version));
    return;
  }
  if (version_known) {
    const bool pascals = version_major_ > 1 || version_minor_ >= kPascalsFromMinor;
    contents_.unit = pascals ? "Pa" : "mbar";
    contents_.unit_from = fmt::format("the log's ver_sw_release is {}; PX4 logs pressure in {} {} v1.{}", version,
                                      contents_.unit, pascals ? "from" : "before", kPascalsFromMinor);
    return;
  }
  // No version, and at most 2000: an atmosphere in mbar, or a vacuum in Pa.
  contents_.unit = largest_value_ >= kSmallestMillibarAtmosphere ? "mbar" : "";
  contents_.unit_from =
      contents_.unit.empty()
          ? fmt::format("the log has no usable ver_sw_release and its largest pressure, {:g}, fits a vacuum in Pa as "
                        "well as mbar",
                        largest_value_)
          : fmt::format("the log has no usable ver_sw_release; its largest pressure, {:g}, is an atmosphere in mbar "
                        "(PX4 before v1.13)",
                        largest_value_);
}

void ULogReader::read_header() {
  const std::size_t got = in_.want(kFileHeaderBytes);
  const std::size_t compared = std::min(got, kULogMagic.size());
  if (compared == 0 || !std::equal(kULogMagic.begin(), kULogMagic.begin() + compared, in_.data(),
                                   [](char a, std::uint8_t b) { return static_cast<std::uint8_t>(a) == b; }))
    in_.fail(0, fmt::format("not a ULog file: expected the magic 'ULog' 01 12 35, found {}",
                            compared == 0 ? std::string("an empty file") : hex_bytes(in_.data(), compared)));
  if (got < kFileHeaderBytes)
    in_.fail(0, fmt::format("the ULog header is cut short: the file holds {} bytes, the header needs {} "
                            "(magic, version, start time)",
                            got, kFileHeaderBytes));
  contents_.format = fmt::format("{} v{}", kULogTitle, in_.data()[7]);
  in_.advance(kFileHeaderBytes);
}

void ULogReader::on_flag_bits(std::uint64_t at, const std::uint8_t* p, std::size_t size) {
  // compat_flags[8], incompat_flags[8], appended_offsets[3] (uint64); more may follow.
  if (size < 16) in_.fail(at, fmt::format("a flag bits message ('B') needs at least 16 bytes, it holds {}", size));
  const std::uint8_t* incompat = p + 8;
  const bool appended = (incompat[0] & 1) != 0;
  bool unknown = (incompat[0] & ~1) != 0;
  for (int i = 1; i < 8; ++i) unknown = unknown || incompat[i] != 0;
  if (unknown)
    in_.fail(at, fmt::format("the log sets incompatible flag bits this reader does not know ({}); the ULog "
                             "spec asks a reader to refuse it",
                             hex_bytes(incompat, 8)));
  if (!appended) return;
  if (size < 40)
    in_.fail(at, fmt::format("the flag bits say data is appended, but the message holds {} bytes, not the 40 "
                             "with the appended offsets",
                             size));
  for (int i = 0; i < 3; ++i)
    if (const std::uint64_t offset = binary::load_u64(p + 16 + 8 * i); offset != 0) {
      if (offset <= at)
        in_.fail(at, fmt::format("appended data at byte {}, before the flag bits message itself", offset));
      appended_offsets_.push_back(offset);
    }
  std::sort(appended_offsets_.begin(), appended_offsets_.end());
}

void ULogReader::on_unsubscription(std::uint64_t at, const std::uint8_t* p, std::size_t size) {
  if (size < 2) in_.fail(at, fmt::format("an unsubscription ('R') needs 2 bytes (msg_id), it holds {}", size));
  subscriptions_.erase(binary::load_u16(p));
}

void ULogReader::on_format(std::uint64_t at, const std::uint8_t* p, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(p), size);
  const std::size_t colon = text.find(':');
  const std::string_view name = colon == std::string_view::npos ? std::string_view() : trimmed(text.substr(0, colon));
  if (name.empty())
    in_.fail(at,
             fmt::format("a format definition ('F') must read 'name:type field;...', it reads '{}'", printable(text)));
  FormatDef def{at, {}};
  std::string_view rest = text.substr(colon + 1);
  while (!rest.empty()) {
    const std::size_t semicolon = rest.find(';');
    const std::string_view item = trimmed(rest.substr(0, semicolon));
    rest = semicolon == std::string_view::npos ? std::string_view() : rest.substr(semicolon + 1);
    if (item.empty()) continue;
    const std::size_t space = item.rfind(' ');
    FieldDef field;
    std::string_view type = space == std::string_view::npos ? std::string_view() : trimmed(item.substr(0, space));
    field.name = space == std::string_view::npos ? std::string() : std::string(item.substr(space + 1));
    if (const std::size_t open = type.find('['); open != std::string_view::npos) {
      const std::string_view count = type.substr(open + 1, type.size() - open - 2);
      const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), field.count);
      if (type.back() != ']' || ec != std::errc() || end != count.data() + count.size() || field.count == 0 ||
          field.count > kMaxFormatBytes)
        in_.fail(at, fmt::format("format '{}': field '{}': expected an array 'type[length] name' with a length "
                                 "of 1 or more, found '{}'",
                                 printable(name), printable(item), printable(type)));
      field.array = true;
      type = type.substr(0, open);
    }
    field.type = std::string(type);
    if (field.type.empty() || field.name.empty())
      in_.fail(at,
               fmt::format("format '{}': expected a field 'type name', found '{}'", printable(name), printable(item)));
    def.fields.push_back(std::move(field));
  }
  if (def.fields.empty()) in_.fail(at, fmt::format("format '{}' has no fields", printable(name)));
  formats_.insert_or_assign(std::string(name), std::move(def));
  format_bytes_.clear();
}

std::size_t ULogReader::size_of_type(const std::string& type, const std::string& within, int depth) {
  if (const BasicType* basic = basic_type(type)) return binary::size_of(basic->kind);
  if (formats_.count(type) == 0) {
    const FormatDef& def = formats_.find(within)->second;
    in_.fail(def.at_byte, fmt::format("format '{}': unknown type '{}' (expected one of {}, or a format the "
                                      "file defines)",
                                      printable(within), printable(type), kBasicTypeList));
  }
  return size_of_format(type, depth + 1);
}

std::size_t ULogReader::size_of_format(const std::string& name, int depth) {
  if (const auto known = format_bytes_.find(name); known != format_bytes_.end()) return known->second;
  const FormatDef& def = formats_.find(name)->second;
  if (depth > kMaxNesting)
    in_.fail(def.at_byte, fmt::format("format '{}' is nested more than {} deep (a format that contains itself?)",
                                      printable(name), kMaxNesting));
  std::size_t bytes = 0;
  for (const FieldDef& field : def.fields) {
    bytes += field.count * size_of_type(field.type, name, depth);
    if (bytes > kMaxFormatBytes)
      in_.fail(def.at_byte, fmt::format("format '{}' is larger than {} bytes, more than any message can hold",
                                        printable(name), kMaxFormatBytes));
  }
  format_bytes_[name] = bytes;
  return bytes;
}

SensorLayout ULogReader::sensor_layout(const std::string& name, std::string_view axes, std::uint64_t subscribed_at,
                                       bool required) {
  const FormatDef& def = formats_.find(name)->second;
  SensorLayout layout;
  std::vector<std::pair<std::string_view, Field*>> wanted = {{"timestamp", &layout.timestamp}};
  Field* const axis_slots[] = {&layout.x, &layout.y, &layout.z};
  const std::vector<std::string_view> axis_names = words_in(axes);
  for (std::size_t i = 0; i < std::min<std::size_t>(axis_names.size(), 3); ++i)
    wanted.emplace_back(axis_names[i], axis_slots[i]);
  const std::size_t n_required = wanted.size();
  wanted.emplace_back("temperature", &layout.temperature);
  wanted.emplace_back("device_id", &layout.device_id);
  std::size_t offset = 0;
  for (const FieldDef& field : def.fields) {
    const std::size_t bytes = field.count * size_of_type(field.type, name, 0);
    for (const auto& [wanted_name, slot] : wanted) {
      if (field.name != wanted_name) continue;
      const BasicType* basic = basic_type(field.type);
      if ((basic == nullptr || field.array) && !required) continue;
      if (basic == nullptr || field.array)
        in_.fail(def.at_byte, fmt::format("format '{}': field '{}' is a '{}{}', expected a number", name, field.name,
                                          printable(field.type), field.array ? fmt::format("[{}]", field.count) : ""));
      *slot = Field{offset, basic->kind, 1.0, true};
      layout.needed_bytes = std::max(layout.needed_bytes, offset + bytes);
    }
    offset += bytes;
  }
  for (std::size_t i = 0; i < n_required && required; ++i)
    if (!wanted[i].second->present) {
      std::string fields;
      for (const FieldDef& field : def.fields) fields += (fields.empty() ? "" : ", ") + field.name;
      std::string expected = "timestamp";
      for (std::size_t j = 1; j < n_required; ++j) expected += fmt::format(", {}", wanted[j].first);
      in_.fail(subscribed_at, fmt::format("the subscribed format '{}' has no field '{}' (it has {}; expected {})",
                                          name, wanted[i].first, printable(fields, 400), expected));
    }
  return layout;
}

void ULogReader::on_subscription(std::uint64_t at, const std::uint8_t* p, std::size_t size) {
  // multi_id (uint8), msg_id (uint16), message_name
  if (size < 4)
    in_.fail(
        at, fmt::format("a subscription ('A') needs multi_id, msg_id and a name (4 bytes or more), it holds {}", size));
  const int multi_id = p[0];
  const std::uint16_t msg_id = binary::load_u16(p + 1);
  const std::string name(trimmed(std::string_view(reinterpret_cast<const char*>(p + 3), size - 3)));
  if (formats_.count(name) == 0)
    in_.fail(at, fmt::format("subscription to '{}' (msg_id {}): no format definition ('F') of that name before it",
                             printable(name), msg_id));
  size_of_format(name, 0);  // every type known, no cycle
  Subscription sub;
  const SensorKind& kind = *contents_.kind;
  if (name == kind.ulog.messages) {
    const std::size_t sensor = sensor_of(multi_id, kind.ulog.messages);
    if (sensor == layouts_.size()) layouts_.push_back(sensor_layout(name, kind.ulog.fields, at));  // a new instance
    sub.sensor = static_cast<int>(sensor);
  }
  if (name == kAccelTopic) {
    sub.accel_layout = sensor_layout(name, "x y z", at, /*required=*/false);
    const SensorLayout& a = sub.accel_layout;
    if (a.x.present && a.y.present && a.z.present) sub.accel = multi_id;  // else not read: only a motion check needs it
  }
  subscriptions_[msg_id] = sub;
}

void ULogReader::on_data(std::uint64_t at, const std::uint8_t* p, std::size_t size) {
  if (size < 2) in_.fail(at, fmt::format("a data message ('D') needs 2 bytes or more (msg_id), it holds {}", size));
  const std::uint16_t msg_id = binary::load_u16(p);
  const auto sub = subscriptions_.find(msg_id);
  if (sub == subscriptions_.end())
    in_.fail(at,
             fmt::format("a data message ('D') for msg_id {}, which no subscription ('A') before it defines", msg_id));
  if (sub->second.accel >= 0) {
    const SensorLayout& a = sub->second.accel_layout;
    if (size - 2 >= a.needed_bytes) take_accel(sub->second.accel, a.x.read(p + 2), a.y.read(p + 2), a.z.read(p + 2));
  }
  if (sub->second.sensor < 0) return;
  const SensorLayout& layout = layouts_[static_cast<std::size_t>(sub->second.sensor)];
  LogSensor& sensor = contents_.sensors[static_cast<std::size_t>(sub->second.sensor)];
  const std::uint8_t* data = p + 2;
  if (size - 2 < layout.needed_bytes)
    in_.fail(at, fmt::format("a {} data message (instance {}) holds {} bytes, its format needs {} for the "
                             "fields read",
                             sensor.message, sensor.instance, size - 2, layout.needed_bytes));
  if (sensor.samples == 0 && layout.device_id.present) {
    const double id = layout.device_id.read(data);  // an integer type in every PX4 version
    sensor.device_id = id >= 0.0 && id <= 4294967295.0 ? static_cast<std::uint32_t>(id) : 0;
  }
  if (const double x = std::abs(layout.x.read(data)); x > largest_value_) largest_value_ = x;
  take_sample(sensor, layout.timestamp.read(data) / 1e6, layout.temperature, layout.x, layout.y, layout.z, data);
}

// Information ('I'): key length (uint8), key "type name", value. Only
// "uint32_t ver_sw_release" is read: 0xAABBCCTT, major AA, minor BB (PX4's
// ulog_file_format.md, "Information Message").
void ULogReader::on_information(std::uint64_t, const std::uint8_t* p, std::size_t size) {
  // Read for a barometer's unit only; one that cannot hold its key leaves the version unknown.
  if (contents_.kind->quantity != Quantity::pressure || size < 1 || size < 1u + p[0]) return;
  const std::string_view key(reinterpret_cast<const char*>(p + 1), p[0]);
  if (key != "uint32_t ver_sw_release" || size < 1u + p[0] + 4) return;
  const std::uint32_t release = binary::load_u32(p + 1 + p[0]);
  version_major_ = static_cast<int>(release >> 24);
  version_minor_ = static_cast<int>((release >> 16) & 0xff);
}

// A parameter ('P'): key length (uint8), key "type name", the value (int32_t
// or float; other types are passed over, as PX4 logs none for calibration).
void ULogReader::on_parameter(std::uint64_t at, const std::uint8_t* p, std::size_t size) {
  if (size < 1 || size < 1u + p[0])
    in_.fail(at, fmt::format("a parameter message ('P') of {} bytes cannot hold its key of {} bytes", size,
                             size < 1 ? 0 : p[0]));
  const std::string_view key(reinterpret_cast<const char*>(p + 1), p[0]);
  const std::size_t space = key.find(' ');
  if (space == std::string_view::npos) return;
  const std::string_view type = key.substr(0, space);
  const std::uint8_t* value = p + 1 + p[0];
  const std::size_t bytes = size - 1 - p[0];
  if (type == "float" && bytes >= 4)
    take_parameter(std::string(key.substr(space + 1)), binary::load_number(Kind::f32, value));
  else if (type == "int32_t" && bytes >= 4)
    take_parameter(std::string(key.substr(space + 1)), binary::load_number(Kind::i32, value));
}

}  // namespace

LogContents read_ulog(const fs::path& file, int instance, const SampleSink& sink, const SensorKind& kind) {
  return binary::read_with<ULogReader>(file, instance, sink, kind);
}

LogFormat ulog_log_format() { return {"ulog", kULogTitle, kULogMagic, read_ulog}; }

}  // namespace gyrotherm::fit
