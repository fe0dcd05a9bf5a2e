#pragma once
// Where a study's record comes from: a log named on the command line (a CSV
// or an autopilot log), or a table of named arrays held by the caller
// (fit/data/table.h: the Python binding's mapping of columns). The studies
// (fit, diagnose, allan, compensate) read through it, so that each runs the
// same on either and only the reading differs.

#include <cstdint>
#include <string>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/data/table.h"

namespace gyrotherm::studies {

class RecordSource {
 public:
  explicit RecordSource(std::string file) : name_(std::move(file)) {}
  // `table` must outlive the source.
  explicit RecordSource(const fit::Table& table) : name_(table.name), table_(&table) {}

  // The file, or the table's name: for messages and reports.
  const std::string& name() const { return name_; }
  const fit::Table* table() const { return table_; }

  // The columns the user gave, to read this record with: for an autopilot
  // log, its three gyro axes when the gyro column is left at its default
  // (fit::columns_for); a table's are as given.
  fit::ColumnMap user_columns(fit::ColumnMap columns) const;
  // The columns a saved fit brings, to read this record with: a table drops
  // the fit's text form and log instance (fit::for_table).
  fit::ColumnMap fit_columns(fit::ColumnMap columns) const;

  // Read and checked into memory (read_measurement_csv, read_table).
  fit::Measurement read(const fit::ColumnMap& columns) const;
  // Prepared: a file by prepare_csv (in one pass when large), a table by
  // prepare_table (always in one pass, straight from its columns). *streamed
  // (if given): whether the record was prepared by the rules of its first
  // kPrefixRows rows (fit/data/streaming.h) — a large file, or a table longer
  // than the prefix — rather than exactly as in memory.
  fit::PreparedData prepare(const fit::PipelineOptions& options, bool* streamed = nullptr) const;
  // Whether prepare_csv would stream this file (never for a table: the
  // in-memory studies copy it, read).
  bool streams(const fit::PipelineOptions& options) const;
  // The file's size, or the table's numbers' (8 bytes each); 0 when unknown.
  std::uintmax_t bytes() const;

 private:
  std::string name_;
  const fit::Table* table_ = nullptr;
};

// The gyro column given for each of a fit file's `channels`: --gyro-col's
// comma list, one per channel in the fit's order, or "" for each when none
// was given (each channel then reads its own). Throws InputError naming the
// option and the fit when the counts differ (a single column would be read
// under every channel's fit).
std::vector<std::string> gyro_per_channel(const std::string& gyro_option, std::size_t channels,
                                          const std::string& fit_file);

}  // namespace gyrotherm::studies
