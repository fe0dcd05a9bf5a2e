#include "fit/data/measurement.h"

#include "fit/data/autopilot_log.h"
#include "fit/data/column_reader.h"
#include "fit/data/csv_dialect.h"
#include "fit/data/csv_parser.h"

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
#include <thread>
#include <tuple>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

std::string_view trim(std::string_view s) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t'; };
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

namespace csv_parsing {

namespace fs = std::filesystem;
using namespace column_rules;

bool is_blank(std::string_view line) { return trim(line).empty(); }

void CsvParser::parse_header(std::string_view line, std::size_t line_number, Measurement& m) {
  try {
    delimiter_ = csv_.delimiter_for(line);
  } catch (const InputError& e) {
    fail(line_number, e.what());
  }
  if (const std::string bad = split_fields(line, delimiter_, fields_); !bad.empty())
    fail(line_number, "the header: " + bad);
  std::vector<std::string> names;
  for (const std::string_view field : fields_) names.push_back(unquote_field(field));
  resolve_columns(std::move(names), line_number, csv_.describe(delimiter_), m);
}

// Reserves for the rows the rest of the file probably holds, judged by the
// length of the first row; bounded by the shortest possible row ("1,2,3\n").
void CsvParser::reserve_for_file(Measurement& m, std::size_t line_bytes) const {
  if (file_bytes_ <= header_end_bytes_) return;
  const auto remaining = static_cast<std::size_t>(file_bytes_ - header_end_bytes_);
  const std::size_t shortest_row = 2 * role_of_column_.size();
  reserve(m, std::min(remaining / std::max<std::size_t>(line_bytes + 1, 1),
                      remaining / std::max<std::size_t>(shortest_row, 1)) +
                 1);
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

void CsvParser::read_log(const fs::path& file, const LogFormat& format, Measurement& m) {
  const SensorKind& kind = map_.units.kind();
  const LogContents contents = format.read(file, -1, {}, kind);
  if (map_.imu && *map_.imu < 0)
    throw InputError(fmt::format("{}: --imu {}: a {} instance is a number from 0 (the log holds {})", name_,
                                 *map_.imu, kind.noun, contents.instances()));
  const int instance = map_.imu.value_or(contents.default_instance());
  if (instance < 0)
    throw InputError(fmt::format("{}: no {} with a temperature to fit against ({})", name_, kind.noun,
                                 contents.describe()));
  const auto sensor = std::find_if(contents.sensors.begin(), contents.sensors.end(),
                                   [&](const LogSensor& g) { return g.instance == instance; });
  if (sensor == contents.sensors.end())
    throw InputError(fmt::format("{}: --imu {}: the log holds {} instances {} ({})", name_, instance, kind.noun,
                                 contents.instances(), contents.describe()));
  // The format states every unit: an option may only repeat it (a unit the
  // reader told from the log's version or values, a ULog's pressure, may be
  // stated otherwise). Units and scales a fit file brings (of the CSV it was
  // fitted on) do not apply; the CSV's form (delimiter, decimal comma,
  // --rate) neither.
  const bool from_fit_file = map_.units.from_fit();
  const bool told = !contents.unit_from.empty();
  const std::array<std::tuple<const std::string*, std::string, const char*>, 3> stated = {
      std::tuple{&map_.units.time, std::string("s"), "--time-unit"},
      {&map_.units.gyro, told ? std::string() : contents.unit, "--gyro-unit"},
      {&map_.units.temp, std::string("C"), "--temp-unit"}};
  for (const auto& [given, unit, option] : stated)
    if (!from_fit_file && !given->empty() && !unit.empty() && *given != unit)
      throw InputError(fmt::format("{}: {} {}: the log is {}, whose units are fixed (time µs, {} {}, "
                                   "temperature °C); leave {} out",
                                   name_, option, *given, contents.format, kind.name, contents.unit, option));
  // A unit the reader told that the fit read otherwise (the user stated it
  // then): not silently one or the other.
  if (told && from_fit_file && !map_.units.gyro.empty() && map_.units.gyro != contents.unit)
    throw InputError(fmt::format("{}: the fit read this {}'s values in {}, but {}{}: give --gyro-unit {} to read "
                                 "them as the fit did, or --gyro-unit {}",
                                 name_, kind.noun, map_.units.gyro, contents.unit_from,
                                 contents.unit.empty() ? "" : fmt::format(" ({})", contents.unit), map_.units.gyro,
                                 contents.unit.empty() ? "Pa or mbar" : contents.unit));
  if (told && contents.unit.empty() && (map_.units.gyro.empty() || from_fit_file))
    throw InputError(fmt::format("{}: the {}'s unit cannot be told: {}; give --gyro-unit Pa or --gyro-unit mbar",
                                 name_, kind.noun, contents.unit_from));
  const Units& scales = map_.units;
  if (!from_fit_file && (scales.gyro_scale != 1.0 || scales.temp_scale != 1.0 || scales.temp_offset != 0.0))
    throw InputError(fmt::format("{}: --gyro-scale, --temp-scale and --temp-offset are for raw counts; the log is {}, "
                                 "in {} and °C",
                                 name_, contents.format, contents.unit));
  csv_ = CsvDialect{};
  parse_header(fmt::format("time_s,temp_c,{}", kind.log_columns), 0, m);
  log_gyro_ = fmt::format("{} instance {}", sensor->message, instance);
  naming_ = RowNaming::sample;
  Units u = units_;
  u.gyro_scale = u.temp_scale = 1.0;
  u.temp_offset = 0.0;
  const bool stated_here = told && !map_.units.gyro.empty() && !from_fit_file;
  // Named strings, not literals: g++ 12 warns of a false overlap when a literal is assigned here.
  static const std::string kSeconds = "s", kCelsius = "C";
  u.time = kSeconds;
  u.gyro = stated_here ? map_.units.gyro : contents.unit;
  u.temp = kCelsius;
  u.time_from = fmt::format("{} timestamps", contents.format);
  u.gyro_from = stated_here ? std::string("--gyro-unit") : fmt::format("{} {}", contents.format, log_gyro_);
  u.temp_from = fmt::format("{} {}", contents.format, log_gyro_);
  u.layout = fmt::format("{}{} chosen; the log holds {}", log_gyro_,
                         sensor->device_id != 0 ? fmt::format(" (device {})", sensor->device_id) : std::string(),
                         contents.describe());
  use_units(u);
  m.units = units_;
  std::size_t sample = 0, without_temperature = 0;
  format.read(
      file, instance,
      [&](double t, double temp, double x, double y, double z) {
        ++sample;
        if (!std::isfinite(temp)) {
          ++without_temperature;
          return;
        }
        const double row[] = {t, temp, x, y, z};
        values_.assign(row, row + 2 + kind.axes());
        take_values(sample, m);
      },
      kind);
  if (without_temperature > 0) {
    units_.layout += fmt::format("; {} of its {} samples have no temperature and are left out", without_temperature,
                                 sample);
    m.units = units_;
  }
  if (rows_ < 2)
    throw InputError(fmt::format("{}: {} has {} samples with a temperature; at least 2 are needed ({})", name_,
                                 log_gyro_, rows_, contents.describe()));
}

void CsvParser::plan_fast_rows() {
  take_.assign(role_of_column_.size(), Take::skip);
  for (std::size_t column = 0; column < take_.size(); ++column)
    if (role_of_column_[column] != kNoRole) take_[column] = Take::number;
  for (const Extra& e : extras_)
    if (e.numeric) take_[e.column] = Take::number;
  if (iso_time_) take_[column_of_[kTime]] = Take::iso_time;
}

bool CsvParser::scan_fields(std::string_view line, const std::vector<Take>& plan, double* values) const {
  const char* p = line.data();
  const char* const end = p + line.size();
  for (std::size_t column = 0; column < plan.size(); ++column) {
    if (column > 0) {
      if (p == end) return false;  // fewer fields than the header
      ++p;                         // the delimiter
    }
    switch (plan[column]) {
      case Take::skip: p = skip_csv_field(p, end, delimiter_); break;
      case Take::number: p = scan_csv_number(p, end, delimiter_, csv_.decimal_comma, values[column]); break;
      case Take::iso_time: {
        Timestamp t;
        p = scan_iso8601_field(p, end, delimiter_, t);
        values[column] = static_cast<double>(t.seconds - time_origin_.seconds) + (t.fraction - time_origin_.fraction);
        break;
      }
    }
    if (p == nullptr) return false;
  }
  return p == end;  // else more fields than the header
}

bool CsvParser::parse_row_fast(std::string_view line, std::size_t line_number, Measurement& m) {
  if (!scan_fields(line, take_, values_.data())) return false;
  take_values(line_number, m);
  return true;
}

void CsvParser::parse_row(std::string_view line, std::size_t line_number, Measurement& m) {
  // Decimal commas between comma delimiters: only quoted fields tell them
  // apart, so every row goes through the quote-aware split.
  const bool commas_twice = csv_.decimal_comma && delimiter_ == ',';
  if (rows_ > 0 && !commas_twice && parse_row_fast(line, line_number, m)) return;
  if (const std::string bad = split_fields(line, delimiter_, fields_); !bad.empty()) fail(line_number, bad);
  const std::size_t fields = fields_.size();
  if (fields != role_of_column_.size())
    fail(line_number, fmt::format("the row has {} field{}, the header (line {}) has {}{}", fields,
                                  fields == 1 ? "" : "s", header_row_, role_of_column_.size(),
                                  commas_twice ? " (with --decimal-comma in a comma-separated file, a number with a "
                                                 "decimal comma must be in quotes: \"20,5\")"
                                               : ""));
  read_row(line_number, m, [&](std::size_t column, double& value) {
    return role_of_column_[column] == kTime ? read_time(fields_[column], m, value)
                                            : parse_csv_number(fields_[column], csv_.decimal_comma, value);
  });
  plan_fast_rows();
}

Measurement CsvParser::read(const fs::path& file) {
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) throw InputError(located(name_, 0, "no such file"));
  if (fs::is_directory(status))
    throw InputError(located(name_, 0, "cannot read: it is a folder, expected a CSV file"));
  Measurement m;
  m.file = name_;
  if (const LogFormat* format = log_format_of(file); format != nullptr) {
    read_log(file, *format, m);
    return m;
  }
  std::unique_ptr<std::FILE, FileCloser> handle(std::fopen(file.c_str(), "rb"));
  if (!handle)
    throw InputError(located(name_, 0, fmt::format("cannot read ({})", std::strerror(errno))));
  file_bytes_ = fs::file_size(file, ec);
  if (ec) file_bytes_ = 0;

  LineReader reader(handle.get());
  std::string_view line;
  std::size_t line_number = 0;
  bool seen_comment = false;
  while (reader.next(line)) {
    ++line_number;
    if (line_number == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
    // UTF-16 (Windows tools' "Unicode text"): a byte-order mark, or a NUL
    // between the characters of the first line.
    if (line_number == 1 && (line.starts_with("\xFF\xFE") || line.starts_with("\xFE\xFF") ||
                             line.find('\0') != std::string_view::npos))
      throw InputError(located(name_, 1,
                               fmt::format("the file is UTF-16 text ({}), expected UTF-8 or ASCII: save it as UTF-8 "
                                           "CSV (e.g. iconv -f UTF-16 -t UTF-8 {} > converted.csv)",
                                           line.starts_with("\xFF\xFE")   ? "byte-order mark FF FE, little-endian"
                                           : line.starts_with("\xFE\xFF") ? "byte-order mark FE FF, big-endian"
                                                                          : "NUL bytes between the characters",
                                           name_)));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (is_blank(line)) continue;
    if (header_row_ == 0) {
      if (line.front() == '#') {
        seen_comment = true;
        continue;
      }
      parse_header(line, line_number, m);
      header_end_bytes_ = reader.consumed_bytes();
      continue;
    }
    if (rows_ == 0 && !streaming()) reserve_for_file(m, line.size());
    parse_row(line, line_number, m);
    if (rows_ == 1 && blocks_possible()) {
      line_number = read_blocks(reader, handle.get(), line_number, m);
      break;
    }
  }
  if (reader.failed()) throw InputError(located(name_, line_number, "cannot read (read error)"));

  if (header_row_ == 0)
    throw InputError(located(
        name_, 0,
        fmt::format("{}, expected a header line naming the columns {}, {}, {}",
                    seen_comment ? "no header (only comments and blank lines)" : "empty file",
                    map_.time, map_.temp, map_.gyro)));
  if (rows_ == 0)
    throw InputError(located(name_, header_row_, "the header is not followed by any data row"));
  if (rows_ < 2)
    throw InputError(located(name_, first_row_, "only 1 data row; at least 2 are needed"));
  return m;
}

}  // namespace csv_parsing

using csv_parsing::CsvParser;

Measurement read_measurement_csv(const std::filesystem::path& file, const ColumnMap& columns) {
  return CsvParser(file, columns).read(file);
}

namespace {

CsvHeader header_of(const Measurement& header_only, const CsvParser& parser) {
  CsvHeader h;
  h.file = header_only.file;
  h.units = header_only.units;
  h.columns = header_only.columns;
  h.has_temp2 = parser.has_temp2();
  h.rows = parser.rows();
  return h;
}

}  // namespace

CsvHeader for_each_row(const std::filesystem::path& file, const ColumnMap& columns,
                       const RowSink& sink, const HeaderSink& on_header) {
  CsvParser parser(file, columns);
  parser.set_sink(sink);
  parser.set_header_sink(on_header);
  const Measurement header_only = parser.read(file);
  return header_of(header_only, parser);
}

CsvHeader for_each_batch(const std::filesystem::path& file, const ColumnMap& columns, std::size_t batch_rows,
                         const BatchSink& sink, const HeaderSink& on_header, unsigned threads,
                         std::size_t block_bytes) {
  CsvParser parser(file, columns);
  parser.set_batch_sink(sink, batch_rows);
  parser.set_header_sink(on_header);
  parser.read_in_blocks(threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency()), block_bytes);
  const Measurement header_only = parser.read(file);
  parser.flush_batch();
  return header_of(header_only, parser);
}

}  // namespace gyrotherm::fit
