#include "studies/record_source.h"

#include <filesystem>
#include <system_error>

#include <fmt/format.h>

#include "fit/channels.h"
#include "fit/data/streaming.h"
#include "sim/util/input_error.h"

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

std::vector<std::string> gyro_per_channel(const std::string& gyro_option, std::size_t channels,
                                          const std::string& fit_file) {
  if (gyro_option.empty()) return std::vector<std::string>(channels);
  std::vector<std::string> gyros = fit::parse_channels(gyro_option);
  if (gyros.size() != channels)
    throw InputError(fmt::format("--gyro-col {}: {} column{} for the {} channel{} of {}; name one column per channel, in "
                                 "the fit's order",
                                 gyro_option, gyros.size(), gyros.size() == 1 ? "" : "s", channels,
                                 channels == 1 ? "" : "s", fit_file));
  return gyros;
}

}  // namespace gyrotherm::studies
