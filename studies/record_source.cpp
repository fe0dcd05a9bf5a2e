#include "studies/record_source.h"

#include <filesystem>
#include <system_error>

#include "fit/data/streaming.h"

namespace gyrotherm::studies {

fit::ColumnMap RecordSource::user_columns(fit::ColumnMap columns) const {
  return table_ ? columns : fit::columns_for(name_, std::move(columns));
}

fit::ColumnMap RecordSource::fit_columns(fit::ColumnMap columns) const {
  return table_ ? fit::for_table(std::move(columns)) : columns;
}

fit::Measurement RecordSource::read(const fit::ColumnMap& columns) const {
  return table_ ? fit::read_table(*table_, columns) : fit::read_measurement_csv(name_, columns);
}

fit::PreparedData RecordSource::prepare(const fit::PipelineOptions& options, bool* streamed) const {
  if (!table_) return fit::prepare_csv(name_, options, streamed);
  fit::PreparedData data = fit::prepare_table(*table_, options);
  if (streamed != nullptr)
    *streamed = data.raw_samples > fit::kPrefixRows && options.columns.extra.empty() && !options.columns.other_numeric;
  return data;
}

bool RecordSource::streams(const fit::PipelineOptions& options) const {
  return !table_ && fit::streams(name_, options);
}

std::uintmax_t RecordSource::bytes() const {
  if (table_) {
    std::uintmax_t numbers = 0;
    for (const fit::TableColumn& c : table_->columns) numbers += c.size;
    return numbers * sizeof(double);
  }
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(name_, error);
  return error ? 0 : size;
}

}  // namespace gyrotherm::studies
