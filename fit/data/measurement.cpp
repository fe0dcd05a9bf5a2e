#include "fit/data/measurement.h"

#include "fit/data/autopilot_log.h"
#include "fit/data/csv_dialect.h"
#include "fit/data/header_units.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string_view>
#include <system_error>
#include <tuple>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

namespace {

namespace fs = std::filesystem;

// Reads a file in fixed blocks and hands out one line at a time (without its
// LF), so a file of any size costs one block of memory plus the longest line.
// std::getline into a std::string would also work, but a block scan with
// memchr is several times faster and lets us count the bytes consumed.
class LineReader {
 public:
  static constexpr std::size_t kBlockBytes = std::size_t{1} << 20;

  explicit LineReader(std::FILE* file) : file_(file), buffer_(kBlockBytes) {}

  // False at the end of the file. The view is valid until the next call.
  bool next(std::string_view& line) {
    for (;;) {
      const char* first = buffer_.data() + begin_;
      const std::size_t available = end_ - begin_;
      if (const void* lf = std::memchr(first, '\n', available)) {
        const auto length = static_cast<std::size_t>(static_cast<const char*>(lf) - first);
        line = std::string_view(first, length);
        begin_ += length + 1;
        consumed_ += length + 1;
        return true;
      }
      if (at_end_) {
        if (available == 0) return false;
        line = std::string_view(first, available);  // a last line without LF
        begin_ = end_;
        consumed_ += available;
        return true;
      }
      refill();
    }
  }

  bool failed() const { return std::ferror(file_) != 0; }
  std::size_t consumed_bytes() const { return consumed_; }

 private:
  // Keeps the partial line at the front, grows the buffer only for a line
  // longer than a block, and reads what fits.
  void refill() {
    if (begin_ > 0) {
      std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
      end_ -= begin_;
      begin_ = 0;
    }
    if (end_ == buffer_.size()) buffer_.resize(buffer_.size() * 2);
    const std::size_t got = std::fread(buffer_.data() + end_, 1, buffer_.size() - end_, file_);
    end_ += got;
    if (got == 0) at_end_ = true;
  }

  std::FILE* file_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0, end_ = 0, consumed_ = 0;
  bool at_end_ = false;
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

bool is_blank(std::string_view line) { return trim(line).empty(); }

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) {
    if (!out.empty()) out += ", ";
    out += n.empty() ? std::string("''") : n;
  }
  return out;
}

// The roles a column can play, in the order of Parsed::value.
enum Role : int { kTime = 0, kTemp = 1, kGyro = 2, kTemp2 = 3, kRoles = 4, kNoRole = -1 };

constexpr std::array<const char*, kRoles> kOptionOf = {"--time-col", "--temp-col", "--gyro-col",
                                                       "--temp2-col"};
constexpr std::array<const char*, kRoles> kWhatOf = {"time", "temperature", "gyro",
                                                     "second temperature"};

// Values no instrument produces: a guard against a wrong column or unit, and
// against numbers whose squares overflow in the fit.
std::string out_of_range(Role role, double v) {
  switch (role) {
    case kTemp:
    case kTemp2:
      if (v < -273.15 || v > 1000.0)
        return fmt::format("{:g} is not a temperature in °C (expected -273.15..1000)", v);
      return {};
    case kGyro:
      if (std::abs(v) > 1e9)
        return fmt::format("{:g} °/h is beyond any gyro's range (|value| <= 1e9 °/h expected; "
                           "is the unit right?)",
                           v);
      return {};
    case kTime:
      if (std::abs(v) > 1e12)
        return fmt::format("{:g} s is not a plausible time (|value| <= 1e12 s expected)", v);
      return {};
    default:
      return {};
  }
}

class CsvParser {
 public:
  CsvParser(const fs::path& file, const ColumnMap& map) : name_(file.string()), map_(map) {
    map_.units.validate();
    map_.csv.validate();
    csv_ = map_.csv;
    use_units(map_.units);
  }

  Measurement read(const fs::path& file);
  // Streaming: every row goes to `sink` instead of being stored.
  void set_sink(RowSink sink) { sink_ = std::move(sink); }
  void set_header_sink(HeaderSink sink) { header_sink_ = std::move(sink); }
  bool has_temp2() const { return has_temp2_; }
  std::size_t rows() const { return rows_; }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& message) const {
    if (!log_gyro_.empty()) throw InputError(fmt::format("{}: sample {} of {}: {}", name_, line, log_gyro_, message));
    throw InputError(located(name_, line, message));
  }
  void use_units(const Units& u) {
    units_ = u;
    time_factor_ = u.time_unit().factor;
    gyro_factor_ = u.gyro_unit().factor;
    temp_in_c_ = u.temp_unit().is_base() && u.temp_scale == 1.0 && u.temp_offset == 0.0;
  }
  // A value read from the file in the units of units_, in s, °C or °/h.
  // (Units' arithmetic, with the unit names looked up once.)
  double convert(Role role, double v) const {
    switch (role) {
      case kTime: return v * time_factor_;
      case kGyro: return units_.gyro_scale * v * gyro_factor_;
      case kTemp:
      case kTemp2: return temp_in_c_ ? v : units_.temp_c(v);
      default: return v;
    }
  }
  void parse_header(std::string_view line, std::size_t line_number, Measurement& m);
  void parse_row(std::string_view line, std::size_t line_number, Measurement& m);
  // The row in values_ (one number per header column, as read): converted,
  // checked, and stored or handed to the sink.
  void take_values(std::size_t line_number, Measurement& m);
  // An autopilot log (fit/data/autopilot_log.h) read as the table
  // time_s, temp_c, gyro_x, gyro_y, gyro_z (s, °C, rad/s) of one gyro.
  void read_log(const fs::path& file, const std::string& format, Measurement& m);
  // The time field of a row, in the file's unit or as an ISO 8601 timestamp
  // (seconds since the first row's): "" on success, else what is wrong.
  std::string read_time(std::string_view field, Measurement& m, double& value);
  void reserve(Measurement& m, std::size_t line_bytes) const;

  std::string name_;
  const ColumnMap& map_;
  Units units_;  // as resolved against the header
  double time_factor_ = 1.0, gyro_factor_ = 1.0;
  bool temp_in_c_ = true;
  std::vector<int> role_of_column_;              // Role of each header column
  char delimiter_ = ',';
  CsvDialect csv_;                               // the text's form (none for an autopilot log)
  std::vector<std::string_view> fields_;         // of the row being read
  std::vector<double> values_;                   // its numbers, by column
  std::string log_gyro_;                         // an autopilot log's gyro ("sensor_gyro instance 1")
  bool iso_time_ = false;                        // the time column holds ISO 8601 timestamps
  Timestamp time_origin_;                        // the first row's, when it does
  // Extra columns: header column → its vector in the measurement, and
  // whether a non-number there is an error (asked for by name) or drops it.
  struct Extra {
    std::size_t column;
    std::string name;
    bool strict;
    bool numeric = true;
  };
  std::vector<Extra> extras_;
  std::array<std::size_t, kRoles> column_of_{};  // header column of each role
  bool has_temp2_ = false;
  std::size_t rows_ = 0;
  double last_time_ = 0.0;
  RowSink sink_;
  HeaderSink header_sink_;
  std::size_t header_line_ = 0, first_row_line_ = 0, previous_line_ = 0;
  std::uintmax_t file_bytes_ = 0, header_end_bytes_ = 0;
};

void CsvParser::parse_header(std::string_view line, std::size_t line_number, Measurement& m) {
  try {
    delimiter_ = csv_.delimiter_for(line);
  } catch (const InputError& e) {
    fail(line_number, e.what());
  }
  if (const std::string bad = split_fields(line, delimiter_, fields_); !bad.empty())
    fail(line_number, "the header: " + bad);
  for (const std::string_view field : fields_) m.columns.push_back(unquote_field(field));
  const std::vector<std::string>& names = m.columns;
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t j = i + 1; j < names.size(); ++j)
      if (!names[i].empty() && names[i] == names[j])
        fail(line_number, fmt::format("column '{}' appears twice in the header (columns {} and {})",
                                      names[i], i + 1, j + 1));

  role_of_column_.assign(names.size(), kNoRole);
  const std::array<const std::string*, kRoles> wanted = {&map_.time, &map_.temp, &map_.gyro,
                                                         &map_.temp2};
  const std::string& default_temp2 = ColumnMap{}.temp2;
  for (int role = 0; role < kRoles; ++role) {
    const std::string& name = *wanted[role];
    const bool optional = role == kTemp2;
    const bool explicit_temp2 = optional && name != default_temp2;
    if (optional && name.empty()) continue;  // temp2 switched off
    const auto it = std::find(names.begin(), names.end(), name);
    if (role == kTime && csv_.rate_hz > 0.0) {  // no time column: rows at 1 / rate
      if (it != names.end())
        fail(line_number, fmt::format("--rate {:g} Hz is for a log without a time column, but column '{}' "
                                      "holds the time (drop --rate, or name another column with --time-col)",
                                      csv_.rate_hz, name));
      continue;
    }
    if (it == names.end()) {
      if (optional && !explicit_temp2) continue;
      fail(line_number,
           fmt::format("no column '{}' (the header has: {}); name the {} column with {}", name,
                       joined(names), kWhatOf[role], kOptionOf[role]));
    }
    const auto column = static_cast<std::size_t>(it - names.begin());
    if (const int other = role_of_column_[column]; other != kNoRole) {
      if (optional && !explicit_temp2) continue;  // e.g. --temp-col temp2_c
      fail(line_number,
           fmt::format("{} and {} both name column '{}'", kOptionOf[other], kOptionOf[role], name));
    }
    role_of_column_[column] = role;
    column_of_[role] = column;
    if (optional) has_temp2_ = true;
  }
  try {
    const auto name_of = [&](int role) {
      const bool absent = (role == kTemp2 && !has_temp2_) || (role == kTime && csv_.rate_hz > 0.0);
      return absent ? std::string() : names[column_of_[role]];
    };
    Units units = resolve_units(map_.units, name_of(kTime), name_of(kTemp), name_of(kGyro), name_of(kTemp2));
    if (csv_.rate_hz > 0.0) {
      if (!units.time_unit().is_base())
        throw InputError(fmt::format("{} gives the time unit {}, but with --rate there is no time column",
                                     units.time_from, units.time));
      units.time_from = fmt::format("--rate {:g} Hz, no time column", csv_.rate_hz);
    }
    units.layout = csv_.describe(delimiter_);
    use_units(units);
  } catch (const InputError& e) {
    fail(line_number, e.what());
  }
  m.units = units_;
  for (const std::string& name : map_.extra) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
      fail(line_number, fmt::format("unknown term '{}': neither a known term (see 'gyrotherm "
                                    "effects') nor step@TIME, nor a column of the log (the header "
                                    "has: {})",
                                    name, joined(names)));
    const auto column = static_cast<std::size_t>(it - names.begin());
    if (role_of_column_[column] != kNoRole)
      fail(line_number, fmt::format("column '{}' is the {} column; it cannot be a model term too", name,
                                    kWhatOf[role_of_column_[column]]));
    extras_.push_back({column, name, true});
  }
  if (map_.other_numeric)
    for (std::size_t column = 0; column < names.size(); ++column) {
      const bool taken = role_of_column_[column] != kNoRole ||
                         std::any_of(extras_.begin(), extras_.end(),
                                     [&](const Extra& e) { return e.column == column; });
      if (!taken && !names[column].empty()) extras_.push_back({column, names[column], false});
    }
  header_line_ = line_number;
}

// Reserves for the rows the rest of the file probably holds, judged by the
// length of the first row; bounded by the shortest possible row ("1,2,3\n").
void CsvParser::reserve(Measurement& m, std::size_t line_bytes) const {
  if (file_bytes_ <= header_end_bytes_) return;
  const auto remaining = static_cast<std::size_t>(file_bytes_ - header_end_bytes_);
  const std::size_t shortest_row = 2 * role_of_column_.size();
  const std::size_t rows = std::min(remaining / std::max<std::size_t>(line_bytes + 1, 1),
                                    remaining / std::max<std::size_t>(shortest_row, 1)) +
                           1;
  m.time_s.reserve(rows);
  m.temp_c.reserve(rows);
  m.gyro_dph.reserve(rows);
  if (has_temp2_) m.temp2_c.reserve(rows);
}

std::string CsvParser::read_time(std::string_view field, Measurement& m, double& value) {
  Timestamp t;
  if (iso_time_) {
    if (!parse_iso8601(unquote_field(field), t))
      return fmt::format("{} is not an ISO 8601 timestamp like the first row's (2026-11-26T05:38:35Z)",
                         shown_field(trim(field)));
    value = static_cast<double>(t.seconds - time_origin_.seconds) + (t.fraction - time_origin_.fraction);
    return {};
  }
  std::string problem = parse_csv_number(field, csv_.decimal_comma, value);
  if (problem.empty() || rows_ > 0 || !parse_iso8601(unquote_field(field), t)) return problem;
  if (!units_.time_unit().is_base())
    return fmt::format("{} is an ISO 8601 timestamp, but {} gives the time unit {}", shown_field(trim(field)),
                       units_.time_from, units_.time);
  iso_time_ = true;
  time_origin_ = t;
  units_.time_from = fmt::format("ISO 8601 timestamps, s since {}", unquote_field(field));
  m.units = units_;
  value = 0.0;
  return {};
}

void CsvParser::read_log(const fs::path& file, const std::string& format, Measurement& m) {
  const bool ulog = format == "ulog";
  const auto read = ulog ? read_ulog : read_dataflash;
  const LogContents contents = read(file, -1, {});
  if (map_.imu && *map_.imu < 0)
    throw InputError(fmt::format("{}: --imu {}: a gyro instance is a number from 0 (the log holds {})", name_,
                                 *map_.imu, contents.instances()));
  const int instance = map_.imu.value_or(contents.default_instance());
  if (instance < 0)
    throw InputError(fmt::format("{}: no gyro with a temperature to fit against ({})", name_, contents.describe()));
  const auto gyro = std::find_if(contents.gyros.begin(), contents.gyros.end(),
                                 [&](const LogGyro& g) { return g.instance == instance; });
  if (gyro == contents.gyros.end())
    throw InputError(fmt::format("{}: --imu {}: the log holds gyro instances {} ({})", name_, instance,
                                 contents.instances(), contents.describe()));
  // The format states every unit: an option may only repeat it. Units and
  // scales a fit file brings (of the CSV it was fitted on) do not apply; the
  // CSV's form (delimiter, decimal comma, --rate) neither.
  const bool from_fit_file = map_.units.gyro_from.starts_with("the fit file");
  const std::array<std::tuple<const std::string*, const char*, const char*>, 3> stated = {
      std::tuple{&map_.units.time, "s", "--time-unit"}, {&map_.units.gyro, "rad/s", "--gyro-unit"},
      {&map_.units.temp, "C", "--temp-unit"}};
  for (const auto& [given, unit, option] : stated)
    if (!from_fit_file && !given->empty() && *given != unit)
      throw InputError(fmt::format("{}: {} {}: the log is {}, whose units are fixed (time µs, gyro rad/s, "
                                   "temperature °C); leave {} out",
                                   name_, option, *given, contents.format, option));
  const Units& scales = map_.units;
  if (!from_fit_file && (scales.gyro_scale != 1.0 || scales.temp_scale != 1.0 || scales.temp_offset != 0.0))
    throw InputError(fmt::format("{}: --gyro-scale, --temp-scale and --temp-offset are for raw counts; the log is {}, "
                                 "in rad/s and °C",
                                 name_, contents.format));
  csv_ = CsvDialect{};
  parse_header("time_s,temp_c,gyro_x,gyro_y,gyro_z", 0, m);
  std::sort(extras_.begin(), extras_.end(), [](const Extra& a, const Extra& b) { return a.column < b.column; });
  log_gyro_ = fmt::format("{} instance {}", gyro->message, instance);
  Units u = units_;
  u.gyro_scale = u.temp_scale = 1.0;
  u.temp_offset = 0.0;
  // Named strings, not literals: g++ 12 warns of a false overlap when a literal is assigned here.
  static const std::string kSeconds = "s", kRadPerSecond = "rad/s", kCelsius = "C";
  u.time = kSeconds;
  u.gyro = kRadPerSecond;
  u.temp = kCelsius;
  u.time_from = fmt::format("{} timestamps", contents.format);
  u.gyro_from = u.temp_from = fmt::format("{} {}", contents.format, log_gyro_);
  u.layout = fmt::format("{}{} chosen; the log holds {}", log_gyro_,
                         gyro->device_id != 0 ? fmt::format(" (device {})", gyro->device_id) : std::string(),
                         contents.describe());
  use_units(u);
  m.units = units_;
  std::size_t sample = 0, without_temperature = 0;
  read(file, instance, [&](double t, double temp, double x, double y, double z) {
    ++sample;
    if (!std::isfinite(temp)) {
      ++without_temperature;
      return;
    }
    values_ = {t, temp, x, y, z};
    take_values(sample, m);
  });
  if (without_temperature > 0) {
    units_.layout += fmt::format("; {} of its {} samples have no temperature and are left out", without_temperature,
                                 sample);
    m.units = units_;
  }
  if (rows_ < 2)
    throw InputError(fmt::format("{}: {} has {} samples with a temperature; at least 2 are needed ({})", name_,
                                 log_gyro_, rows_, contents.describe()));
}

void CsvParser::parse_row(std::string_view line, std::size_t line_number, Measurement& m) {
  if (const std::string bad = split_fields(line, delimiter_, fields_); !bad.empty()) fail(line_number, bad);
  const std::size_t fields = fields_.size();
  if (fields != role_of_column_.size())
    fail(line_number, fmt::format("the row has {} field{}, the header (line {}) has {}", fields,
                                  fields == 1 ? "" : "s", header_line_, role_of_column_.size()));
  values_.assign(fields, 0.0);
  std::size_t next_extra = 0;  // extras_ in header order (see read())
  for (std::size_t column = 0; column < fields; ++column) {
    const std::string_view field = fields_[column];
    for (; next_extra < extras_.size() && extras_[next_extra].column == column; ++next_extra) {
      Extra& e = extras_[next_extra];
      if (!e.numeric) continue;
      const std::string problem = parse_csv_number(field, csv_.decimal_comma, values_[column]);
      if (!problem.empty()) {
        if (e.strict) fail(line_number, fmt::format("column {}: {}", e.name, problem));
        e.numeric = false;  // a column of text, say: not a candidate
        m.extra.erase(e.name);
      }
    }
    if (const int role = role_of_column_[column]; role != kNoRole) {
      const std::string problem = role == kTime ? read_time(field, m, values_[column])
                                                : parse_csv_number(field, csv_.decimal_comma, values_[column]);
      if (!problem.empty()) fail(line_number, fmt::format("column {}: {}", m.columns[column], problem));
    }
  }
  take_values(line_number, m);
}

void CsvParser::take_values(std::size_t line_number, Measurement& m) {
  std::array<double, kRoles> value{};
  for (const Extra& e : extras_)
    if (e.numeric && !sink_) m.extra[e.name].push_back(values_[e.column]);
  for (std::size_t column = 0; column < values_.size(); ++column) {
    const int role = role_of_column_[column];
    if (role < 0 || role >= kRoles) continue;  // kNoRole
    const double read = values_[column];
    value[role] = convert(static_cast<Role>(role), read);
    const std::string range = out_of_range(static_cast<Role>(role), value[role]);
    if (!range.empty())
      fail(line_number,
           fmt::format("column {}: {}{}", m.columns[column], range,
                       read == value[role] ? std::string()
                                           : fmt::format(" (read {:g}, converted by {})", read, units_.description())));
  }
  if (csv_.rate_hz > 0.0) {
    value[kTime] = static_cast<double>(rows_) / csv_.rate_hz;
    if (const std::string range = out_of_range(kTime, value[kTime]); !range.empty())
      fail(line_number, fmt::format("row {} at --rate {:g} Hz: {}", rows_, csv_.rate_hz, range));
  }
  if (rows_ == 0 && header_sink_) header_sink_(CsvHeader{m.file, m.units, m.columns, has_temp2_, 0});
  if (rows_ > 0 && !(value[kTime] > last_time_))
    fail(line_number,
         fmt::format("column {}: time {} is not after {} on line {} (time must be strictly "
                     "increasing{})",
                     m.columns[column_of_[kTime]], value[kTime], last_time_, previous_line_,
                     iso_time_ ? "; read as seconds since the first row's timestamp" : ""));
  last_time_ = value[kTime];
  if (sink_) {
    sink_(value[kTime], value[kTemp], value[kGyro], has_temp2_ ? value[kTemp2] : 0.0);
  } else {
    m.time_s.push_back(value[kTime]);
    m.temp_c.push_back(value[kTemp]);
    m.gyro_dph.push_back(value[kGyro]);
    if (has_temp2_) m.temp2_c.push_back(value[kTemp2]);
  }
  if (rows_ == 0) first_row_line_ = line_number;
  previous_line_ = line_number;
  ++rows_;
}

Measurement CsvParser::read(const fs::path& file) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) throw InputError(located(name_, 0, "no such file"));
  if (fs::is_directory(status))
    throw InputError(located(name_, 0, "cannot read: it is a folder, expected a CSV file"));
  Measurement m;
  m.file = name_;
  if (const std::string format = autopilot_log_format(file); !format.empty()) {
    read_log(file, format, m);
    return m;
  }
  std::unique_ptr<std::FILE, FileCloser> handle(std::fopen(file.c_str(), "rb"));
  if (!handle)
    throw InputError(located(name_, 0, fmt::format("cannot read ({})", std::strerror(errno))));
  file_bytes_ = fs::file_size(file, ec);
  if (ec) file_bytes_ = 0;

  LineReader reader(handle.get());
  const auto by_column = [](const Extra& a, const Extra& b) { return a.column < b.column; };
  std::string_view line;
  std::size_t line_number = 0;
  bool seen_comment = false;
  while (reader.next(line)) {
    ++line_number;
    if (line_number == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (is_blank(line)) continue;
    if (header_line_ == 0) {
      if (line.front() == '#') {
        seen_comment = true;
        continue;
      }
      parse_header(line, line_number, m);
      std::sort(extras_.begin(), extras_.end(), by_column);
      header_end_bytes_ = reader.consumed_bytes();
      continue;
    }
    if (rows_ == 0 && !sink_) reserve(m, line.size());
    parse_row(line, line_number, m);
  }
  if (reader.failed()) throw InputError(located(name_, line_number, "cannot read (read error)"));

  if (header_line_ == 0)
    throw InputError(located(
        name_, 0,
        fmt::format("{}, expected a header line naming the columns {}, {}, {}",
                    seen_comment ? "no header (only comments and blank lines)" : "empty file",
                    map_.time, map_.temp, map_.gyro)));
  if (rows_ == 0)
    throw InputError(located(name_, header_line_, "the header is not followed by any data row"));
  if (rows_ < 2)
    throw InputError(located(name_, first_row_line_, "only 1 data row; at least 2 are needed"));
  return m;
}

}  // namespace

Measurement read_measurement_csv(const std::filesystem::path& file, const ColumnMap& columns) {
  return CsvParser(file, columns).read(file);
}

CsvHeader for_each_row(const std::filesystem::path& file, const ColumnMap& columns,
                       const RowSink& sink, const HeaderSink& on_header) {
  CsvParser parser(file, columns);
  parser.set_sink(sink);
  parser.set_header_sink(on_header);
  const Measurement header_only = parser.read(file);
  CsvHeader h;
  h.file = header_only.file;
  h.units = header_only.units;
  h.columns = header_only.columns;
  h.has_temp2 = parser.has_temp2();
  h.rows = parser.rows();
  return h;
}

}  // namespace gyrotherm::fit
