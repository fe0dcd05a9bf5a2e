#pragma once
// A record held by the caller as named columns of numbers (a Python mapping
// of column names to 1-D float64 arrays, say), read by the rules of the
// measurement CSV (fit/data/measurement.h, docs/contracts.md) — the same
// rules, in one place (fit/data/column_reader.h):
//
//   columns  time, temperature, gyro and the optional second temperature
//            found by their ColumnMap names (--time-col … --temp2-col), or an
//            InputError naming the option and the columns the table has;
//            --rate for a table without time; the extra columns
//            (ColumnMap::extra, other_numeric) as the CSV reader reads them;
//   units    ColumnMap::units, else the unit the column's name states
//            ('time (ms)', fit/data/header_units.h), else the base unit;
//   values   every needed value finite and in an instrument's range, time
//            strictly increasing, at least 2 rows.
//
// Every column of a table has the same length (a table is rows, as a CSV's
// lines are). A row is named by its index from 0, as Python counts:
// "arrays: index 56: column gyro_dph: nan is not a finite number".
//
// The CSV's text options (--delimiter, --decimal-comma) and an autopilot
// log's --imu have nothing to apply to: given for a table, they are refused.

#include <cstddef>
#include <string>
#include <vector>

#include "fit/data/measurement.h"
#include "fit/data/prepare.h"

namespace gyrotherm::fit {

struct TableColumn {
  std::string name;
  const double* values = nullptr;  // `size` numbers, held by the caller
  std::size_t size = 0;
};

// Columns held by the caller (numpy arrays): never copied by prepare_table,
// and to outlive every call given them.
struct Table {
  std::string name = "arrays";  // for messages, and as PreparedData::file / Measurement::file
  std::vector<TableColumn> columns;
};

// The table's needed and extra columns, converted and checked, copied into a
// Measurement (for the in-memory paths: diagnose, allan, compensate). Throws
// InputError naming the table, the index and the column on bad input.
Measurement read_table(const Table& table, const ColumnMap& columns);

// The same reading and checks, every row handed to `sink` (temp2_c is 0
// without that column), nothing stored; on_header (if given) once before the
// first row. Extra columns are checked but not handed over.
CsvHeader for_each_row(const Table& table, const ColumnMap& columns, const RowSink& sink,
                       const HeaderSink& on_header = {});

// The table prepared in one pass (fit/data/streaming.h), its rows read
// straight from the caller's columns (no reading thread, no copy): memory is
// the prefix (kPrefixRows rows), the glitch filter's window and the averaged
// series. A table of up to kPrefixRows rows is prepared exactly as
// prepare_data(read_table(...)) is; a longer one as a large CSV streamed by
// prepare_data_streaming (the interval, glitch floor and burst decision of
// its first kPrefixRows rows). With extra columns as model terms
// (options.columns.extra, other_numeric): read_table, then prepare_data.
PreparedData prepare_table(const Table& table, const PipelineOptions& options);

// The map without what a fit file made on a text file or log brings and a
// table has nothing to apply to: the CSV's delimiter and decimal comma, and
// the log's gyro instance (compensate and allan read a table with a fit's
// columns; --rate and the units do apply).
ColumnMap for_table(ColumnMap columns);

}  // namespace gyrotherm::fit
