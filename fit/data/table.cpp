#include "fit/data/table.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "fit/data/column_reader.h"
#include "fit/data/one_pass.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using namespace column_rules;

// A table's rows read by the column rules (fit/data/column_reader.h).
class TableReader : public ColumnReader {
 public:
  TableReader(const Table& table, const ColumnMap& map) : ColumnReader(table.name, map, RowNaming::index), table_(table) {
    const auto text_only = [&](const std::string& option) {
      throw InputError(located(name_, 0, fmt::format("{} applies to text files (CSV) only; a table holds numbers", option)));
    };
    if (!map.csv.delimiter.empty() && map.csv.delimiter != "auto") text_only("--delimiter " + map.csv.delimiter);
    if (map.csv.decimal_comma) text_only("--decimal-comma");
    if (map.imu)
      throw InputError(located(name_, 0, fmt::format("--imu {} applies to autopilot logs only, not to a table", *map.imu)));
  }

  Measurement read() {
    Measurement m;
    m.file = name_;
    std::vector<std::string> names;
    for (const TableColumn& c : table_.columns) {
      if (c.values == nullptr && c.size > 0)
        throw InputError(located(name_, 0, fmt::format("column {}: no values (a null pointer for {})", c.name, c.size)));
      names.push_back(c.name);
    }
    resolve_columns(std::move(names), 0, std::string(), m);
    const std::size_t rows = check_lengths();
    if (!streaming()) reserve(m, rows);
    for (std::size_t i = 0; i < rows; ++i)
      read_row(i, m, [&](std::size_t column, double& value) {
        value = table_.columns[column].values[i];
        return std::isfinite(value) ? std::string() : fmt::format("{} is not a finite number", value);
      });
    return m;
  }

 private:
  // The rows: every column's length, which must be one; at least 2.
  std::size_t check_lengths() const {
    const std::vector<TableColumn>& columns = table_.columns;
    const std::size_t rows = columns.empty() ? 0 : columns.front().size;
    for (const TableColumn& c : columns)
      if (c.size != rows)
        throw InputError(located(name_, 0, fmt::format("column {} has {} values, column {} has {}: every column of a "
                                                       "table needs the same length",
                                                       c.name, c.size, columns.front().name, rows)));
    if (rows < 2)
      throw InputError(located(name_, 0, fmt::format("{} row{}; at least 2 are needed", rows, rows == 1 ? "" : "s")));
    return rows;
  }

  const Table& table_;
};

}  // namespace

Measurement read_table(const Table& table, const ColumnMap& columns) { return TableReader(table, columns).read(); }

CsvHeader for_each_row(const Table& table, const ColumnMap& columns, const RowSink& sink, const HeaderSink& on_header) {
  TableReader reader(table, columns);
  reader.set_sink(sink);
  reader.set_header_sink(on_header);
  const Measurement header_only = reader.read();
  return CsvHeader{header_only.file, header_only.units, header_only.columns, reader.has_temp2(), reader.rows()};
}

PreparedData prepare_table(const Table& table, const PipelineOptions& options) {
  if (!options.columns.extra.empty() || options.columns.other_numeric)
    return prepare_data(read_table(table, options.columns), options);
  options.outliers.validate();
  options.averaging.validate();
  one_pass::Preparer preparer(options, table.name);
  for_each_row(
      table, options.columns,
      [&](double t, double temp, double gyro, double temp2) { preparer.add({t, temp, gyro, temp2}); },
      [&](const CsvHeader& header) { preparer.set_header(header); });
  return preparer.finish();
}

ColumnMap for_table(ColumnMap columns) {
  columns.csv.delimiter.clear();
  columns.csv.decimal_comma = false;
  columns.imu.reset();
  return columns;
}

}  // namespace gyrotherm::fit
