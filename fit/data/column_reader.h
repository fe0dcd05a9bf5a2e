#pragma once
// The rules a record's columns are read by, whatever holds them: for
// fit/data/measurement.cpp (a CSV's header and fields, an autopilot log's
// samples) and fit/data/table.cpp (a caller's named arrays) only.
//
//   columns  each role (time, temperature, gyro, second temperature) found
//            by its ColumnMap name, or a message naming the option and the
//            columns there are; --rate for a record without time; the extra
//            columns (ColumnMap::extra by name, other_numeric the rest);
//   units    from ColumnMap::units, else from the column's name, else the
//            base unit (resolve_units, fit/data/header_units.h);
//   rows     each needed value converted to s, °C or °/h, held to the range
//            an instrument gives (out_of_range), time strictly increasing,
//            then stored in a Measurement or handed to a RowSink.
//
// A row is named in messages as the source counts them: a CSV's physical
// line ("data.csv:57: …"), a log's sample ("log.ulg: sample 57 of …: …") or
// a table's index from 0 ("arrays: index 56: …").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "fit/data/measurement.h"

namespace gyrotherm::fit::column_rules {

// The roles a column can play, in the order of ColumnReader's values.
enum Role : int { kTime = 0, kTemp = 1, kGyro = 2, kTemp2 = 3, kRoles = 4, kNoRole = -1 };

inline constexpr std::array<const char*, kRoles> kOptionOf = {"--time-col", "--temp-col", "--gyro-col",
                                                              "--temp2-col"};
inline constexpr std::array<const char*, kRoles> kWhatOf = {"time", "temperature", "gyro", "second temperature"};

// Values no instrument produces: a guard against a wrong column or unit, and
// against numbers whose squares overflow in the fit. "" when `v` is plausible
// (in_range, the test alone).
inline bool in_range(Role role, double v) {
  switch (role) {
    case kTemp:
    case kTemp2: return !(v < -273.15 || v > 1000.0);
    case kGyro: return !(std::abs(v) > 1e9);
    case kTime: return !(std::abs(v) > 1e12);
    default: return true;
  }
}
std::string out_of_range(Role role, double v, const SensorKind& kind = sensor_kind(""));

// "a, b, ''": column names for a message.
std::string joined(const std::vector<std::string>& names);
// "; 'imu.acc.x', 'imu.acc.y' may be the accelerometer's: give --sensor accel
// --gyro-col …": the columns whose name says a sensor kind's role or unit,
// for the error of a measured column not found (empty when none does).
std::string sensor_columns_hint(const std::vector<std::string>& names, const SensorKind& wanted);

// How a source numbers its rows in messages.
enum class RowNaming {
  line,    // a CSV's physical line, from 1: "file:57: …"
  sample,  // an autopilot log's sample, from 1: "file: sample 57 of GYRO: …"
  index,   // a table's row, from 0: "name: index 56: …"
};

class ColumnReader {
 public:
  // Validates the units and the CSV options (InputError naming the option).
  ColumnReader(std::string name, const ColumnMap& map, RowNaming naming);

  // Streaming: every row goes to `sink` instead of being stored.
  void set_sink(RowSink sink) { sink_ = std::move(sink); }
  // Or in batches of `rows` rows (flush_batch hands on the last).
  void set_batch_sink(BatchSink sink, std::size_t rows) {
    batch_sink_ = std::move(sink);
    batch_rows_ = std::max<std::size_t>(rows, 1);
    batch_.reserve(batch_rows_);
  }
  void flush_batch() {
    if (!batch_.empty()) batch_sink_(batch_);
    batch_.clear();
  }
  void set_header_sink(HeaderSink sink) { header_sink_ = std::move(sink); }
  bool has_temp2() const { return has_temp2_; }
  std::size_t rows() const { return rows_; }

 protected:
  [[noreturn]] void fail(std::size_t row, const std::string& message) const;
  void use_units(const Units& u);
  // A value read in the units of units_, in s, °C or °/h (Units' arithmetic,
  // with the unit names looked up once).
  double convert(Role role, double v) const {
    switch (role) {
      case kTime: return v * time_factor_;
      case kGyro: return units_.gyro_scale * v * gyro_factor_;
      case kTemp:
      case kTemp2: return temp_in_c_ ? v : units_.temp_c(v);
      default: return v;
    }
  }
  // The columns `names` (m.columns), at row `header_row` for messages (0:
  // none): duplicates refused, each role's column, the units (`layout`: how
  // the text was read, Units::layout) and the extra columns, in column order.
  void resolve_columns(std::vector<std::string> names, std::size_t header_row, std::string layout, Measurement& m);
  // One row: parse(column, value&) reads the value of a needed or extra column
  // and returns "" or what is wrong with it — an error in a needed column or
  // an extra asked for by name, and in another extra column that column is
  // dropped (it holds something else: not a candidate). Then take_values.
  template <class Parse>
  void read_row(std::size_t row, Measurement& m, Parse&& parse) {
    values_.assign(role_of_column_.size(), 0.0);
    std::size_t next_extra = 0;  // extras_ in column order
    for (std::size_t column = 0; column < role_of_column_.size(); ++column) {
      for (; next_extra < extras_.size() && extras_[next_extra].column == column; ++next_extra) {
        Extra& e = extras_[next_extra];
        if (!e.numeric) continue;
        if (const std::string problem = parse(column, values_[column]); !problem.empty()) {
          if (e.strict) fail(row, "column " + e.name + ": " + problem);
          e.numeric = false;
          m.extra.erase(e.name);
        }
      }
      if (role_of_column_[column] != kNoRole)
        if (const std::string problem = parse(column, values_[column]); !problem.empty())
          fail(row, "column " + m.columns[column] + ": " + problem);
    }
    take_values(row, m);
  }
  // The row in values_ (one number per column, as read): converted, checked,
  // and stored or handed to the sink.
  void take_values(std::size_t row, Measurement& m);
  // Room for `rows` rows of the needed columns.
  void reserve(Measurement& m, std::size_t rows) const;

  std::string name_;
  const ColumnMap& map_;
  RowNaming naming_;
  std::string log_gyro_;  // an autopilot log's gyro ("sensor_gyro instance 1")
  Units units_;           // as resolved against the names
  double time_factor_ = 1.0, gyro_factor_ = 1.0;
  bool temp_in_c_ = true;
  CsvDialect csv_;                   // the text's form and --rate (none for an autopilot log)
  std::vector<int> role_of_column_;  // Role of each column
  struct Needed {
    std::size_t column;
    Role role;
  };
  std::vector<Needed> needed_;  // the columns with a role, in column order
  std::vector<double> values_;       // the row's numbers, by column
  bool iso_time_ = false;            // the time column holds ISO 8601 timestamps
  // Extra columns: column → its vector in the measurement, and whether a
  // non-number there is an error (asked for by name) or drops it.
  struct Extra {
    std::size_t column;
    std::string name;
    bool strict;
    bool numeric = true;
  };
  std::vector<Extra> extras_;
  std::array<std::size_t, kRoles> column_of_{};  // column of each role
  bool has_temp2_ = false;
  std::size_t rows_ = 0;
  std::size_t header_row_ = 0, first_row_ = 0, previous_row_ = 0;
  double last_time_ = 0.0;
  RowSink sink_;
  BatchSink batch_sink_;
  std::size_t batch_rows_ = 0;
  std::vector<RowValues> batch_;
  HeaderSink header_sink_;
  // Rows go to a sink rather than into the Measurement.
  bool streaming() const { return sink_ || batch_sink_; }

 private:
  // "on line 5", "at index 5": a row as the message names it.
  std::string row_name(std::size_t row) const;
};

}  // namespace gyrotherm::fit::column_rules
