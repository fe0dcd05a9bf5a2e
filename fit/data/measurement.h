#pragma once
// Reading a measurement CSV (docs/contracts.md, "Measurement CSV").
//
// Grammar, one physical line at a time (lines end in LF or CRLF; a UTF-8 byte
// order mark at the start of the file is skipped):
//
//   file    = { comment | blank } header { row | blank }
//   comment = "#" anything          (only before the header)
//   blank   = only spaces, tabs      (anywhere)
//   header  = name { d name }        (names trimmed of spaces and tabs)
//   row     = field { d field }      (exactly as many fields as the header)
//
// d is the delimiter: a comma unless the header uses semicolons or tabs more,
// or --delimiter says (fit/data/csv_dialect.h, with the decimal comma, RFC
// 4180 quotes, ISO 8601 timestamps and --rate for a log without time).
//
// The columns the pipeline needs — time (s), temperature (°C), gyro output (°/h)
// and, if present, the second temperature (°C) — are found by name (ColumnMap,
// the CLI's --time-col, --temp-col, --gyro-col, --temp2-col) and must hold
// finite decimal numbers (std::from_chars, general format; surrounding spaces
// and a leading '+' are accepted). Other columns may hold anything. Time must be
// strictly increasing; at least two data rows are required.
//
// Every violation throws gyrotherm::InputError naming the file, the physical
// line number (1-based, counting comments and blank lines) and the column, and
// what was expected, e.g. "data.csv:57: column gyro_dph: 'abc' is not a number".
//
// The file is read in blocks of a fixed size and parsed line by line, so the
// memory is that of the result, not of the text.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fit/data/csv_dialect.h"
#include "fit/data/sensor_kind.h"
#include "fit/data/units.h"

namespace gyrotherm::fit {

// How the numbers of the needed columns become seconds, °C and °/h (the
// units every report and JSON uses), by the units of fit/data/units.h:
//
//   time    = t · factor of --time-unit;
//   gyro    = K · g · factor of --gyro-unit, K = --gyro-scale (a logger's
//             counts, or its bug);
//   temp    = c(A · x + B) for temp_c and temp2_c, A = --temp-scale,
//             B = --temp-offset (raw counts), c the --temp-unit → °C.
//
// A unit name left empty is not given: the reader takes the one the
// column's name states, else the base unit (fit/data/header_units.h), and
// records where each came from in *_from ("--time-unit", "header 'time (ms)'",
// "default").
// The name a fit given in memory (a Python FitResult never saved) goes by
// where a fit file's path would be (fit::load_fits_json, reports).
inline constexpr const char* kFitInMemory = "fit (in memory)";

struct Units {
  std::string time, gyro, temp;
  // The kind of sensor the measured ("gyro") column is (--sensor; empty: a
  // gyro): its quantity is the one `gyro` names a unit of.
  std::string sensor;
  const SensorKind& kind() const;
  std::string time_from, gyro_from, temp_from;
  // A unit a saved fit brings that its own record's header (or the default)
  // gave, not an option: a record whose header states another unit is read
  // in that (the header wins); one that states none is read in the fit's.
  // Units typed as options when fitting carry over as given.
  bool time_weak = false, gyro_weak = false, temp_weak = false;
  // How the file's text was read, when not plain comma-separated with decimal
  // points ("semicolon-separated, decimal comma"; CsvDialect::describe).
  std::string layout;
  // The table's entries, the base unit for an empty name (throw InputError
  // naming the option for an unknown name).
  const Unit& time_unit() const;
  const Unit& gyro_unit() const;
  const Unit& temp_unit() const;
  double gyro_scale = 1.0;
  double temp_scale = 1.0;
  double temp_offset = 0.0;

  // Throws InputError naming the option, the value and what is allowed.
  void validate() const;
  // Every unit taken from a saved fit: "the fit file FILE", or "the fit given
  // in memory" for FILE kFitInMemory (a Python FitResult never saved), put
  // before what each *_from holds (the fit file's ", ORIGIN when fitting");
  // from_fit() tells such units from those a record's header or options gave.
  void set_from_fit(const std::string& file);
  bool from_fit() const;
  bool identity() const;
  double time_s(double t) const;
  double gyro_dph(double g) const;
  double temp_c(double x) const;
  // "time ms → s; gyro 0.5 × rad/s → °/h; temp 0.00390625 × counts − 231 → °C",
  // or "none" when nothing is converted.
  std::string description() const;
  // "time ms (header 'time (ms)'), gyro rad/s (--gyro-unit), temperature C (default)".
  std::string used() const;
};

// The names of the needed columns in the file's header, and their units.
struct ColumnMap {
  std::string time = "time_s";    // seconds, strictly increasing (--time-col)
  std::string temp = "temp_c";    // gyro temperature sensor, °C (--temp-col)
  std::string gyro = "gyro_dph";  // gyro output, °/h (--gyro-col)
  std::string temp2 = "temp2_c";  // optional second sensor, °C (--temp2-col): the default
                                  // name may be absent, another name must exist, and an
                                  // empty name ignores the column
  Units units;                    // applied as each value is read
  CsvDialect csv;                 // delimiter, decimal comma, --rate
  // An autopilot log's gyro instance (--imu; default: the first with a
  // temperature). Such a log (fit/data/autopilot_log.h) reads as the columns
  // time_s, temp_c, gyro_x, gyro_y, gyro_z of that gyro (s, °C, rad/s).
  std::optional<int> imu;
  // Other columns to read as numbers, for model terms named after them
  // (fit/model/terms.h): each must exist and hold numbers. With
  // other_numeric, every further column that holds only numbers is read too
  // (diagnose tries them as candidates); a column with anything else is left.
  std::vector<std::string> extra;
  bool other_numeric = false;

  // A map that sets nothing (empty names and units, NaN scales and rate): what an
  // option set holds when every option keeps another map's value.
  static ColumnMap unset();
  // This map with each name, unit and scale `given` sets in place of its own.
  ColumnMap with(const ColumnMap& given) const;
};

struct Measurement {
  std::string file;  // as given to the reader, for messages
  Units units;       // as read: every unit name set (fit/data/header_units.h)
  std::vector<double> time_s, temp_c, gyro_dph;
  std::vector<double> temp2_c;       // empty when the file has no such column
  // The extra columns read (ColumnMap::extra, other_numeric), as written.
  std::map<std::string, std::vector<double>, std::less<>> extra;
  std::vector<std::string> columns;  // the header as read (trimmed)
  bool has_temp2() const { return !temp2_c.empty(); }
  std::size_t size() const { return time_s.size(); }
};

// The columns to read `file` with when the measured column is left at its
// default: an autopilot log's three axes of the kind (gyro_x, gyro_y,
// gyro_z; one channel each); a CSV's kind's default column (gyro_dph,
// accel_mps2) when its header has it, else its columns by role: the one
// column whose name names the kind or states one of its units (GyrX,
// imu.acc.x, AccX, accel_x_mps2, press (hPa)), or three such with the axes
// x, y and z, as "x,y,z" (a model's, a truth's or a compensation's column
// left out). Anything else keeps the default, and the reader's error lists
// the columns that may be meant.
ColumnMap columns_for(const std::filesystem::path& file, ColumnMap columns);

// The text without the spaces and tabs at either end (a field, a column's name).
std::string_view trim(std::string_view s);

// Reads and checks a measurement CSV; throws InputError (see above) on bad input.
Measurement read_measurement_csv(const std::filesystem::path& file, const ColumnMap& columns = {});

// Streaming: the same reading and checks, but every row is handed to `sink`
// (temp2_c is 0 when the file has no such column) and nothing is stored.
using RowSink = std::function<void(double time_s, double temp_c, double gyro_dph, double temp2_c)>;
struct CsvHeader {
  std::string file;
  Units units;  // as read
  std::vector<std::string> columns;
  bool has_temp2 = false;
  std::size_t rows = 0;
};
// on_header (if given) is called once, after the header and before the first row.
using HeaderSink = std::function<void(const CsvHeader& header)>;
CsvHeader for_each_row(const std::filesystem::path& file, const ColumnMap& columns,
                       const RowSink& sink, const HeaderSink& on_header = {});

// The same, a batch of rows at a time: `sink` takes the rows in `batch` (it
// may swap in an empty vector with room) and is called on the calling thread,
// in the file's order. A CSV's rows after the first are parsed in blocks of
// `block_bytes` (0: a megabyte; tests take small ones to cross many block
// boundaries) on `threads` more threads (0: one per core) while the batches
// are handed on; a row the block parse does not take (quotes, an error, time
// not increasing) is read again line by line, so every value and every
// message is for_each_row's.
struct RowValues {
  double t, temp, gyro, temp2;  // s, °C, °/h, °C (0 without that column)
};
using BatchSink = std::function<void(std::vector<RowValues>& batch)>;
CsvHeader for_each_batch(const std::filesystem::path& file, const ColumnMap& columns, std::size_t batch_rows,
                         const BatchSink& sink, const HeaderSink& on_header = {}, unsigned threads = 0,
                         std::size_t block_bytes = 0);

}  // namespace gyrotherm::fit
