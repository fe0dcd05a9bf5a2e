// fit/data/table.h: a record as named arrays is read by the CSV reader's
// rules — the same numbers, units and messages (rows by index from 0) — and
// prepared in one pass exactly as in memory, or as a streamed CSV when longer
// than the prefix.

#include "fit/data/table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "fit/data/streaming.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"
#include "table_test_data.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

void expect_same_measurement(const Measurement& a, const Measurement& b) {
  const auto numbers = [](const Measurement& m) {
    return std::tie(m.time_s, m.temp_c, m.gyro_dph, m.temp2_c, m.extra, m.columns);
  };
  const auto units = [](const Measurement& m) {
    const Units& u = m.units;
    return std::tie(u.time, u.gyro, u.temp, u.time_from, u.gyro_from, u.temp_from, u.layout);
  };
  EXPECT_TRUE(numbers(a) == numbers(b));
  EXPECT_TRUE(units(a) == units(b)) << a.units.used() << " vs " << b.units.used();
}

TEST(Table, ReadsTheSameNumbersAsTheCsvReaderToTheLastBit) {
  ScratchDir dir;
  const OwnedColumns c = thermal_record(5000, 1.0, 1);
  c.write_csv(dir / "r.csv");
  for (const bool other_numeric : {false, true}) {
    ColumnMap columns;
    columns.other_numeric = other_numeric;
    if (!other_numeric) columns.extra = {"heater_w"};
    const Measurement csv = read_measurement_csv(dir / "r.csv", columns);
    const Measurement table = read_table(c.table("my arrays"), columns);
    EXPECT_EQ(table.file, "my arrays");
    ASSERT_EQ(table.size(), 5000u);
    ASSERT_TRUE(table.has_temp2());
    EXPECT_EQ(table.extra.count("heater_w"), 1u);
    expect_same_measurement(table, csv);
    EXPECT_EQ(table.time_s[17], c.values[0][17]);  // not converted: s, °C, °/h by the names
  }
}

// A thermal record's columns, written as r.csv in `dir` too, and prepared
// from the columns in one pass with the default options.
struct OnePass {
  OnePass(const ScratchDir& dir, std::size_t rows, double rate_hz, unsigned seed)
      : columns(thermal_record(rows, rate_hz, seed)), table(columns.table()) {
    columns.write_csv(dir / "r.csv");
    prepared = prepare_table(table, options);
  }
  OwnedColumns columns;
  Table table;
  PipelineOptions options;
  PreparedData prepared;
};

TEST(Table, WithinThePrefixPreparesExactlyAsInMemory) {
  // 20 000 samples at 1 Hz with glitches: prepare_table (one pass, no copy)
  // equals prepare_data on read_table and on the CSV, bit for bit.
  ScratchDir dir;
  const OnePass r(dir, 20000, 1.0, 2);
  const Table& table = r.table;
  const PipelineOptions& o = r.options;
  const PreparedData& one_pass = r.prepared;
  const PreparedData in_memory = prepare_data(read_table(table, o.columns), o);
  const PreparedData from_csv = prepare_data(dir / "r.csv", o);
  ASSERT_LT(one_pass.raw_samples, kPrefixRows);
  EXPECT_GE(one_pass.outliers.removed, 2u);
  EXPECT_EQ(one_pass.file, "arrays");
  EXPECT_TRUE(one_pass.has_temp2());
  expect_identical(one_pass, in_memory);
  expect_identical(one_pass, from_csv);
  // A log column as a model term goes through read_table and prepare_data.
  PipelineOptions with_extra = o;
  with_extra.columns.extra = {"heater_w"};
  const PreparedData extra = prepare_table(table, with_extra);
  ASSERT_EQ(extra.series.extra.count("heater_w"), 1u);
  expect_identical(extra, prepare_data(dir / "r.csv", with_extra));
}

TEST(Table, UnitsFromTheColumnsNameFromTheOptionsOrTheDefault) {
  OwnedColumns c;
  c.add("time (ms)", {0.0, 500.0, 1000.0});
  c.add("temp_c", {20.0, 21.0, 22.0});
  c.add("gyro_dph", {1.0, 2.0, 3.0});
  ColumnMap columns;
  columns.time = "time (ms)";
  const Measurement by_name = read_table(c.table(), columns);
  EXPECT_EQ(by_name.time_s, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(by_name.units.time, "ms");
  EXPECT_EQ(by_name.units.time_from, "header 'time (ms)'");
  EXPECT_EQ(by_name.units.gyro_from, "header 'gyro_dph'");

  // --gyro-unit dps on a column whose name says nothing; the temperature by default.
  c.names = {"t", "temperature", "rate"};
  columns.time = "t";
  columns.temp = "temperature";
  columns.gyro = "rate";
  columns.units.gyro = "dps";
  const Measurement by_option = read_table(c.table(), columns);
  EXPECT_EQ(by_option.time_s, (std::vector<double>{0.0, 500.0, 1000.0}));
  EXPECT_EQ(by_option.gyro_dph, (std::vector<double>{3600.0, 7200.0, 10800.0}));
  EXPECT_EQ(by_option.units.gyro_from, "--gyro-unit");
  EXPECT_EQ(by_option.units.temp_from, "default");
  // The option and the name disagree: said as the CSV reader says it.
  c.names[0] = "time (ms)";
  columns.time = "time (ms)";
  columns.units.time = "s";
  expect_input_error([&] { read_table(c.table(), columns); }, {"arrays: ", "time (ms)", "--time-unit"});
}

TEST(Table, RateGivesTheTimeOfATableWithout) {
  OwnedColumns c;
  c.add("temp_c", {20.0, 20.1, 20.2, 20.3});
  c.add("gyro_dph", {1.0, 1.1, 1.2, 1.3});
  ColumnMap columns;
  columns.csv.rate_hz = 10.0;
  const Measurement m = read_table(c.table(), columns);
  EXPECT_EQ(m.time_s, (std::vector<double>{0.0, 0.1, 0.2, 0.3}));
  EXPECT_EQ(m.units.time_from, "--rate 10 Hz, no time column");
  c.add("time_s", {0.0, 1.0, 2.0, 3.0});
  expect_input_error([&] { read_table(c.table(), columns); },
                     {"arrays: --rate 10 Hz is for a log without a time column, but column 'time_s' holds the time"});
}

TEST(Table, EveryBadInputIsNamedWithTheIndexFromZeroAndTheColumn) {
  const OwnedColumns good = thermal_record(100, 1.0, 3);
  const auto refused = [&](const std::function<void(OwnedColumns&, ColumnMap&)>& spoil,
                           const std::vector<std::string>& message) {
    OwnedColumns c = good;
    ColumnMap columns;
    spoil(c, columns);
    expect_input_error([&] { read_table(c.table(), columns); }, message);
    // The one-pass preparation refuses it alike.
    PipelineOptions o;
    o.columns = columns;
    expect_input_error([&] { prepare_table(c.table(), o); }, message);
  };
  constexpr double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  refused([&](OwnedColumns& c, ColumnMap&) { c["gyro_dph"][56] = nan; },
          {"arrays: index 56: column gyro_dph: nan is not a finite number"});
  refused([&](OwnedColumns& c, ColumnMap&) { c["temp_c"][0] = inf; },
          {"arrays: index 0: column temp_c: inf is not a finite number"});
  refused([&](OwnedColumns& c, ColumnMap&) { c["time_s"][99] = -inf; },
          {"arrays: index 99: column time_s: -inf is not a finite number"});
  refused([&](OwnedColumns& c, ColumnMap&) { c["temp_c"][7] = 5000.0; },
          {"arrays: index 7: column temp_c: 5000 is not a temperature in °C"});
  refused([&](OwnedColumns& c, ColumnMap&) { c["time_s"][3] = c["time_s"][2]; },
          {"arrays: index 3: column time_s: time 1002 is not after 1002 at index 2 (time must be strictly increasing)"});
  refused([&](OwnedColumns& c, ColumnMap&) { c["temp_c"].pop_back(); },
          {"arrays: column temp_c has 99 values, column time_s has 100", "the same length"});
  refused(
      [&](OwnedColumns& c, ColumnMap&) {
        for (auto& v : c.values) v.resize(1);
      },
      {"arrays: 1 row; at least 2 are needed"});
  refused(
      [&](OwnedColumns& c, ColumnMap&) {
        for (auto& v : c.values) v.clear();
      },
      {"arrays: 0 rows; at least 2 are needed"});
  refused([&](OwnedColumns&, ColumnMap& m) { m.gyro = "rate"; },
          {"arrays: no column 'rate' (the table has: time_s, temp_c, gyro_dph, temp2_c, heater_w); name the gyro "
           "column with --gyro-col"});
  refused([&](OwnedColumns&, ColumnMap& m) { m.gyro = "temp_c"; },
          {"arrays: --temp-col and --gyro-col both name column 'temp_c'"});
  refused([&](OwnedColumns& c, ColumnMap&) { c.names[4] = "temp_c"; },
          {"arrays: column 'temp_c' appears twice in the table (columns 1 and 4)"});
  refused([&](OwnedColumns&, ColumnMap& m) { m.csv.delimiter = "semicolon"; },
          {"arrays: --delimiter semicolon applies to text files (CSV) only"});
  refused([&](OwnedColumns&, ColumnMap& m) { m.csv.decimal_comma = true; },
          {"arrays: --decimal-comma applies to text files (CSV) only"});
  refused([&](OwnedColumns&, ColumnMap& m) { m.imu = 1; }, {"arrays: --imu 1 applies to autopilot logs only"});
  refused([&](OwnedColumns&, ColumnMap& m) { m.extra = {"fan"}; },
          {"arrays: unknown term 'fan'", "(the table has: time_s, temp_c, gyro_dph, temp2_c, heater_w)"});
  refused(
      [&](OwnedColumns& c, ColumnMap& m) {
        m.extra = {"heater_w"};
        c["heater_w"][42] = nan;
      },
      {"arrays: index 42: column heater_w: nan is not a finite number"});
}

TEST(Table, AColumnOfOtherNumbersWithANonFiniteValueIsNoCandidate) {
  // As the CSV reader leaves a column that is not all numbers.
  OwnedColumns c = thermal_record(100, 1.0, 4);
  c["heater_w"][10] = std::numeric_limits<double>::quiet_NaN();
  c.add("fan", std::vector<double>(100, 1.0));
  ColumnMap columns;
  columns.other_numeric = true;
  const Measurement m = read_table(c.table(), columns);
  EXPECT_EQ(m.extra.count("heater_w"), 0u);
  ASSERT_EQ(m.extra.count("fan"), 1u);
  EXPECT_EQ(m.extra.at("fan").size(), 100u);
}

TEST(Table, ANullColumnIsRefusedNotRead) {
  const OwnedColumns c = thermal_record(10, 1.0, 5);
  Table t = c.table();
  t.columns[2].values = nullptr;
  expect_input_error([&] { read_table(t, {}); }, {"arrays: column gyro_dph: no values (a null pointer for 10)"});
}

TEST(Table, AFitFilesTextFormIsDroppedForATable) {
  ColumnMap fitted;
  fitted.csv.delimiter = "semicolon";
  fitted.csv.decimal_comma = true;
  fitted.csv.rate_hz = 10.0;
  fitted.imu = 2;
  const ColumnMap t = for_table(fitted);
  EXPECT_EQ(t.csv.delimiter, "");
  EXPECT_FALSE(t.csv.decimal_comma);
  EXPECT_FALSE(t.imu.has_value());
  EXPECT_EQ(t.csv.rate_hz, 10.0);
}

TEST(Table, LongerThanThePrefixPreparesAndFitsAsTheStreamedCsv) {
  // 300 000 samples at 10 Hz (8.3 h): beyond the prefix, so both one-pass
  // routes take Δ, the glitch floor and the burst decision from the first
  // kPrefixRows rows and the report's scale from every 1000th sample; the
  // table's rows are the CSV's numbers, so everything is the same to the bit.
  ScratchDir dir;
  const OnePass r(dir, 300000, 10.0, 6);
  const Table& table = r.table;
  const PipelineOptions& o = r.options;
  const PreparedData& one_pass = r.prepared;
  const PreparedData streamed = prepare_data_streaming(dir / "r.csv", o);
  ASSERT_GT(one_pass.raw_samples, kPrefixRows);
  EXPECT_GE(one_pass.outliers.removed, 30u);
  expect_identical(one_pass, streamed);
  const std::vector<const Term*> terms = parse_formula("T + T^2 + dT");
  const EngineInfo& ols = find_engine("ols");
  const ModelFit a = fit_model(one_pass, terms, ols, {});
  const ModelFit b = fit_model(streamed, terms, ols, {});
  EXPECT_EQ(a.coefficients.intercept, b.coefficients.intercept);
  EXPECT_EQ(a.coefficients.b, b.coefficients.b);
  EXPECT_EQ(a.instability_after_dph, b.instability_after_dph);
  // And close to the in-memory preparation of the whole record.
  const PreparedData in_memory = prepare_data(read_table(table, o.columns), o);
  EXPECT_EQ(one_pass.outliers.times_s, in_memory.outliers.times_s);
  EXPECT_NEAR(one_pass.outliers.floor_dph / in_memory.outliers.floor_dph, 1.0, 0.01);
  ASSERT_EQ(one_pass.series.size(), in_memory.series.size());
  for (std::size_t p = 0; p < in_memory.series.size(); ++p)
    EXPECT_NEAR(one_pass.series.gyro_dph[p], in_memory.series.gyro_dph[p], 1e-12) << p;
}

}  // namespace
}  // namespace gyrotherm::fit
