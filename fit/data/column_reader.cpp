// The rules a record's columns are read by (fit/data/column_reader.h): the
// roles, units and extra columns of the names, and each row's checks.
#include "fit/data/column_reader.h"

#include <cctype>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "fit/data/column_role.h"
#include "fit/data/header_units.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit::column_rules {

std::string out_of_range(Role role, double v, const SensorKind& kind) {
  if (in_range(role, v)) return {};
  switch (role) {
    case kTemp:
    case kTemp2:
      if (v < -273.15 || v > 1000.0)
        return fmt::format("{:g} is not a temperature in °C (expected -273.15..1000; if the column holds raw counts, "
                           "give --temp-scale and --temp-offset: temperature = A x column + B)",
                           v);
      return {};
    case kGyro:
      if (std::abs(v) > 1e9)
        return fmt::format("{:g} {} is beyond any {}'s range (|value| <= 1e9 {} expected; "
                           "is the unit right?)",
                           v, kind.unit, kind.noun, kind.unit);
      return {};
    case kTime:
      if (std::abs(v) > 1e12) return fmt::format("{:g} s is not a plausible time (|value| <= 1e12 s expected)", v);
      return {};
    default:
      return {};
  }
}

std::string sensor_columns_hint(const std::vector<std::string>& names, const SensorKind& wanted) {
  // The columns each kind's role or unit names (imu.acc.x, AccX, accel_x_mps2,
  // press (hPa)): the measured column(s) the user may have meant.
  std::string out;
  std::vector<const SensorKind*> kinds{&wanted};  // its own first, then the others
  for (const SensorKind& k : sensor_kinds())
    if (&k != &wanted) kinds.push_back(&k);
  for (const SensorKind* k : kinds) {
    std::vector<std::string> found;
    for (const std::string& n : names)
      if (role_by_name(n) != ColumnRole::derived && (unit_in_header(k->quantity, n).unit != nullptr || names_sensor(n, *k)))
        found.push_back(n);
    if (found.empty()) continue;
    const std::string list = joined(found), quoted = fmt::format("'{}'", fmt::join(found, ","));
    if (k == &wanted)
      out += fmt::format("; {} may be the {}'s: give --gyro-col {}", list, k->noun, quoted);
    else
      out += fmt::format("; {} may be the {}'s: to fit {}, give --sensor {} --gyro-col {}", list, k->noun,
                         found.size() == 1 ? "it" : "them", k->name, quoted);
  }
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) {
    if (!out.empty()) out += ", ";
    out += n.empty() ? std::string("''") : n;
  }
  return out;
}

ColumnReader::ColumnReader(std::string name, const ColumnMap& map, RowNaming naming)
    : name_(std::move(name)), map_(map), naming_(naming) {
  map_.units.validate();
  map_.csv.validate();
  csv_ = map_.csv;
  use_units(map_.units);
}

void ColumnReader::fail(std::size_t row, const std::string& message) const {
  switch (naming_) {
    case RowNaming::sample: throw InputError(fmt::format("{}: sample {} of {}: {}", name_, row, log_gyro_, message));
    case RowNaming::index: throw InputError(fmt::format("{}: index {}: {}", name_, row, message));
    case RowNaming::line: break;
  }
  throw InputError(located(name_, row, message));
}

std::string ColumnReader::row_name(std::size_t row) const {
  return fmt::format("{} {}", naming_ == RowNaming::index ? "at index" : "on line", row);
}

void ColumnReader::use_units(const Units& u) {
  units_ = u;
  time_factor_ = u.time_unit().factor;
  gyro_factor_ = u.gyro_unit().factor;
  temp_in_c_ = u.temp_unit().is_base() && u.temp_scale == 1.0 && u.temp_offset == 0.0;
}

void ColumnReader::resolve_columns(std::vector<std::string> names_given, std::size_t header_row, std::string layout,
                                   Measurement& m) {
  const bool table = naming_ == RowNaming::index;
  // A table's problems with its names are the table's, at no row.
  const auto fail_names = [&](const std::string& message) {
    if (table) throw InputError(located(name_, 0, message));
    fail(header_row, message);
  };
  const char* const holder = table ? "the table" : "the header";
  m.columns = std::move(names_given);
  const std::vector<std::string>& names = m.columns;
  const std::size_t first = table ? 0 : 1;  // how columns are counted: as rows are
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t j = i + 1; j < names.size(); ++j)
      if (!names[i].empty() && names[i] == names[j])
        fail_names(fmt::format("column '{}' appears twice in {} (columns {} and {})", names[i], holder, i + first,
                               j + first));

  role_of_column_.assign(names.size(), kNoRole);
  const std::array<const std::string*, kRoles> wanted = {&map_.time, &map_.temp, &map_.gyro, &map_.temp2};
  const std::string& default_temp2 = ColumnMap{}.temp2;
  for (int role = 0; role < kRoles; ++role) {
    const std::string& name = *wanted[role];
    const bool optional = role == kTemp2;
    const bool explicit_temp2 = optional && name != default_temp2;
    if (optional && name.empty()) continue;  // temp2 switched off
    const auto it = std::find(names.begin(), names.end(), name);
    if (role == kTime && csv_.rate_hz > 0.0) {  // no time column: rows at 1 / rate
      if (it != names.end())
        fail_names(fmt::format("--rate {:g} Hz is for a log without a time column, but column '{}' "
                               "holds the time (drop --rate, or name another column with --time-col)",
                               csv_.rate_hz, name));
      continue;
    }
    if (it == names.end()) {
      if (optional && !explicit_temp2) continue;
      // A column that differs only in case or separators ("Temp C" for
      // temp_c): said first, as the likely one.
      std::string near;
      for (const std::string& n : names)
        if (!n.empty() && folded_name(n) == folded_name(name)) near = fmt::format(" (did you mean '{}'?)", n);
      const SensorKind& kind = map_.units.kind();
      fail_names(fmt::format("no column '{}'{} ({} has: {}); name the {} column with {}{}", name, near, holder,
                             joined(names), role == kGyro ? std::string(kind.noun) : std::string(kWhatOf[role]),
                             kOptionOf[role], role == kGyro ? sensor_columns_hint(names, kind) : std::string()));
    }
    const auto column = static_cast<std::size_t>(it - names.begin());
    if (const int other = role_of_column_[column]; other != kNoRole) {
      if (optional && !explicit_temp2) continue;  // e.g. --temp-col temp2_c
      fail_names(fmt::format("{} and {} both name column '{}'", kOptionOf[other], kOptionOf[role], name));
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
    units.layout = std::move(layout);
    use_units(units);
  } catch (const InputError& e) {
    fail_names(e.what());
  }
  m.units = units_;
  for (const std::string& name : map_.extra) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
      fail_names(fmt::format("unknown term '{}': neither a known term (see 'gyrotherm "
                             "effects') nor step@TIME, nor a column of the log ({} has: {})",
                             name, holder, joined(names)));
    const auto column = static_cast<std::size_t>(it - names.begin());
    if (role_of_column_[column] != kNoRole)
      fail_names(fmt::format("column '{}' is the {} column; it cannot be a model term too", name,
                             kWhatOf[role_of_column_[column]]));
    extras_.push_back({column, name, true});
  }
  if (map_.other_numeric)
    for (std::size_t column = 0; column < names.size(); ++column) {
      const bool taken = role_of_column_[column] != kNoRole ||
                         std::any_of(extras_.begin(), extras_.end(), [&](const Extra& e) { return e.column == column; });
      if (!taken && !names[column].empty()) extras_.push_back({column, names[column], false});
    }
  std::sort(extras_.begin(), extras_.end(), [](const Extra& a, const Extra& b) { return a.column < b.column; });
  needed_.clear();
  for (std::size_t column = 0; column < names.size(); ++column)
    if (role_of_column_[column] != kNoRole) needed_.push_back({column, static_cast<Role>(role_of_column_[column])});
  values_.assign(names.size(), 0.0);
  header_row_ = header_row;
}

void ColumnReader::reserve(Measurement& m, std::size_t rows) const {
  m.time_s.reserve(rows);
  m.temp_c.reserve(rows);
  m.gyro_dph.reserve(rows);
  if (has_temp2_) m.temp2_c.reserve(rows);
}

void ColumnReader::take_values(std::size_t row, Measurement& m) {
  std::array<double, kRoles> value{};
  for (const Extra& e : extras_)
    if (e.numeric && !streaming()) m.extra[e.name].push_back(values_[e.column]);
  for (const auto [column, role] : needed_) {
    const auto r = static_cast<std::size_t>(role);
    if (r >= kRoles) continue;  // never: needed_ holds roles (g++ cannot tell)
    const double read = values_[column];
    value[r] = convert(role, read);
    if (!in_range(role, value[r]))
      fail(row, fmt::format("column {}: {}{}", m.columns[column], out_of_range(role, value[r], map_.units.kind()),
                            read == value[r] ? std::string()
                                             : fmt::format(" (read {:g}, converted by {})", read, units_.description())));
  }
  if (csv_.rate_hz > 0.0) {
    value[kTime] = static_cast<double>(rows_) / csv_.rate_hz;
    if (const std::string range = out_of_range(kTime, value[kTime]); !range.empty())
      fail(row, fmt::format("row {} at --rate {:g} Hz: {}", rows_, csv_.rate_hz, range));
  }
  if (rows_ == 0 && header_sink_) header_sink_(CsvHeader{m.file, m.units, m.columns, has_temp2_, 0});
  if (rows_ > 0 && !(value[kTime] > last_time_))
    fail(row, fmt::format("column {}: time {} is not after {} {} (time must be strictly increasing{})",
                          m.columns[column_of_[kTime]], value[kTime], last_time_, row_name(previous_row_),
                          iso_time_ ? "; read as seconds since the first row's timestamp" : ""));
  last_time_ = value[kTime];
  if (batch_sink_) {
    batch_.push_back({value[kTime], value[kTemp], value[kGyro], has_temp2_ ? value[kTemp2] : 0.0});
    if (batch_.size() >= batch_rows_) flush_batch();
  } else if (sink_) {
    sink_(value[kTime], value[kTemp], value[kGyro], has_temp2_ ? value[kTemp2] : 0.0);
  } else {
    m.time_s.push_back(value[kTime]);
    m.temp_c.push_back(value[kTemp]);
    m.gyro_dph.push_back(value[kGyro]);
    if (has_temp2_) m.temp2_c.push_back(value[kTemp2]);
  }
  if (rows_ == 0) first_row_ = row;
  previous_row_ = row;
  ++rows_;
}

}  // namespace gyrotherm::fit::column_rules
