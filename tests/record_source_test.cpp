// studies/record_source.h: every study run on a table of arrays gives what it
// gives on the log the arrays were read from — fit, diagnose, allan and
// compensate, their JSON equal but for the record's name.

#include "studies/record_source.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "fit/data/streaming.h"
#include "fit/model/formula.h"
#include "studies/allan/allan_study.h"
#include "studies/diagnose/diagnose_run.h"
#include "studies/fit/compensate_run.h"
#include "studies/fit/fit_run.h"
#include "table_test_data.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;
using Json = nlohmann::json;

// `text` with every occurrence of `from` made `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// The JSON of the log's run with the log's name made the table's.
// A log's fit JSON as the same numbers given as arrays give it: named
// "arrays", and without the file's SHA-256 (arrays have no bytes to hash).
Json as_table(const std::string& json_text, const std::string& log) {
  Json j = Json::parse(replaced(json_text, log, "arrays"));
  const auto unhashed = [](Json& fit) {
    if (fit.contains("data") && fit["data"].is_object()) fit["data"].erase("sha256");
  };
  unhashed(j);
  if (j.contains("channels"))
    for (Json& c : j["channels"]) unhashed(c);
  return j;
}
// A report's JSON as parsed back (keys in order), to compare with as_table's.
Json parsed(const nlohmann::ordered_json& j) { return Json::parse(j.dump()); }

// A fit's JSON without its engine's time (which differs run to run).
Json untimed(Json j) {
  if (j.contains("channels"))
    for (Json& c : j["channels"]) c.erase("seconds");
  j.erase("seconds");
  return j;
}

// The simulated warm-up (8 h at 1 Hz, with its truth) and its numeric columns as a table's.
struct Simulated {
  ScratchDir dir;
  std::string log;
  OwnedColumns columns;
  Simulated() : log((dir / "log.csv").string()) {
    simulate_shipped(dir, "warmup", "", "log.csv");
    columns = columns_of_csv(log);
  }
};

TEST(RecordSource, FitOnATableIsTheFitOnItsLog) {
  Simulated s;
  FitRequest r;
  r.data = s.log;
  r.terms = fit::parse_formula("T + T^2 + dT");
  const FitRun on_log = run_fit(r);
  const fit::Table table = s.columns.table();
  r.data = "ignored.csv";
  const FitRun on_table = run_fit(r, table, load_truth_beside(s.log));
  ASSERT_EQ(on_table.channels.size(), 1u);
  const ChannelFit &a = on_log.channels.front(), &b = on_table.channels.front();
  EXPECT_EQ(b.result.coefficients.intercept, a.result.coefficients.intercept);
  EXPECT_EQ(b.result.coefficients.b, a.result.coefficients.b);
  ASSERT_TRUE(a.truth && b.truth);
  EXPECT_EQ(on_table.request.data, "arrays");
  EXPECT_FALSE(b.streamed);
  const Json j = Json::parse(on_table.json);
  EXPECT_EQ(j["data"]["file"], "arrays");
  EXPECT_TRUE(j.contains("coefficient_error"));
  EXPECT_EQ(untimed(j), untimed(as_table(on_log.json, s.log)));
  EXPECT_NE(fit_text(on_table).find("data: arrays: 28"), std::string::npos) << fit_text(on_table);
  // Without the truth, none is added.
  EXPECT_FALSE(Json::parse(run_fit(r, table).json).contains("truth"));
}

TEST(RecordSource, FitOfSeveralChannelsOfATableIsTheFitOfTheirLog) {
  Simulated s;
  std::vector<double> mirrored = s.columns["gyro_dph"];
  for (double& g : mirrored) g = 3.0 - g;
  s.columns.add("gyro_b", mirrored);
  s.columns.write_csv(s.dir / "two.csv");
  FitRequest r;
  r.data = (s.dir / "two.csv").string();
  r.terms = fit::parse_formula("T + dT");
  r.pipeline.columns.gyro = "gyro_dph,gyro_b";
  const FitRun on_log = run_fit(r);
  const FitRun on_table = run_fit(r, s.columns.table(), load_truth_beside(s.log));
  ASSERT_EQ(on_table.channels.size(), 2u);
  EXPECT_FALSE(on_table.channels[0].truth) << "the truth belongs to one gyro column";
  EXPECT_EQ(on_table.channels[1].result.coefficients.b, on_log.channels[1].result.coefficients.b);
  EXPECT_EQ(untimed(Json::parse(on_table.json)), untimed(as_table(on_log.json, r.data)));
}

TEST(RecordSource, DiagnoseOnATableIsDiagnoseOnItsLog) {
  // In memory, with the table's other columns (chamber_c, case_c, …) as candidates as the log's.
  Simulated s;
  DiagnoseRequest r;
  r.data = s.log;
  r.base_terms = r.terms = fit::parse_formula("T + T^2");
  const DiagnoseRun on_log = run_diagnose(r);
  const DiagnoseRun on_table = run_diagnose(r, s.columns.table());
  EXPECT_FALSE(on_table.channels.front().report.diagnosis.columns_tried.empty());
  EXPECT_EQ(on_table.channels.front().measurement.file, "arrays");
  EXPECT_EQ(parsed(diagnose_json(on_table)), as_table(diagnose_json(on_log).dump(), s.log));
  EXPECT_EQ(diagnose_text(on_table), replaced(diagnose_text(on_log), s.log, "arrays"));
}

TEST(RecordSource, AllanOnATableIsAllanOnItsLogRawAndCompensated) {
  Simulated s;
  const fit::Table table = s.columns.table();
  AllanRequest r;
  r.data = s.log;
  EXPECT_EQ(parsed(allan_json(run_allan(r, table))), as_table(allan_json(run_allan(r)).dump(), s.log));
  FitRequest f;
  f.data = s.log;
  f.terms = fit::parse_formula("T + T^2 + dT");
  f.output = (s.dir / "fit.json").string();
  run_fit(f);
  r.fit_file = f.output;
  const std::vector<AllanStudy> compensated = run_allan(r, table);
  ASSERT_EQ(compensated.front().series.size(), 2u);
  EXPECT_EQ(parsed(allan_json(compensated)), as_table(allan_json(run_allan(r)).dump(), s.log));
}

TEST(RecordSource, CompensateOnATableIsCompensateOnItsLog) {
  Simulated s;
  const fit::Table table = s.columns.table();
  FitRequest f;
  f.data = s.log;
  f.terms = fit::parse_formula("T + T^2 + dT");
  f.output = (s.dir / "fit.json").string();
  run_fit(f);
  for (const bool causal : {false, true}) {
    CompensateRequest r;
    r.data = s.log;
    r.fit_file = f.output;
    r.causal = causal;
    const CompensateRun on_table = run_compensate(r, table);
    EXPECT_EQ(on_table.request.data, "arrays");
    EXPECT_EQ(parsed(compensate_json(on_table)), as_table(compensate_json(run_compensate(r)).dump(), s.log));
  }
}

TEST(RecordSource, AFitOfASemicolonFileCompensatesATableButADelimiterGivenForItIsRefused) {
  // The fit's CSV form describes its file, not the table: dropped. One given
  // for the table is refused.
  Simulated s;
  ASSERT_EQ(run_shell(s.dir, "tr , ';' < log.csv | tee semi.csv").exit_code, 0);
  FitRequest f;
  f.data = (s.dir / "semi.csv").string();
  f.terms = fit::parse_formula("T + dT");
  f.pipeline.columns.csv.delimiter = "semicolon";
  f.output = (s.dir / "fit.json").string();
  run_fit(f);
  CompensateRequest r;
  r.fit_file = f.output;
  const CompensateRun run = run_compensate(r, s.columns.table());
  EXPECT_GT(run.channels.front().ratio(), 1.0);
  r.columns.csv.delimiter = "tab";
  expect_input_error([&] { run_compensate(r, s.columns.table()); }, {"arrays: --delimiter tab applies to text files"});
}

TEST(RecordSource, ATableIsReadAsGivenAndSaysWhenItWasPreparedByItsPrefix) {
  const OwnedColumns c = thermal_record(fit::kPrefixRows + 1, 10.0, 7);
  const fit::Table table = c.table();
  const RecordSource source(table);
  EXPECT_EQ(source.name(), "arrays");
  EXPECT_EQ(source.table(), &table);
  EXPECT_EQ(source.bytes(), 5 * (fit::kPrefixRows + 1) * sizeof(double));
  fit::PipelineOptions o;
  EXPECT_FALSE(source.streams(o)) << "the in-memory studies copy a table";
  bool streamed = false;
  EXPECT_EQ(source.prepare(o, &streamed).raw_samples, fit::kPrefixRows + 1);
  EXPECT_TRUE(streamed) << "one row past the prefix: its rules are the prefix's";
  o.columns.extra = {"heater_w"};
  source.prepare(o, &streamed);
  EXPECT_FALSE(streamed) << "a log column as a term: read into memory";
  // A table's columns are as given; a fit's text form is dropped for it, kept for a file.
  fit::ColumnMap semicolon;
  semicolon.csv.delimiter = "semicolon";
  EXPECT_EQ(source.user_columns(semicolon).csv.delimiter, "semicolon");
  EXPECT_EQ(source.fit_columns(semicolon).csv.delimiter, "");
  EXPECT_EQ(RecordSource("log.csv").fit_columns(semicolon).csv.delimiter, "semicolon");
  EXPECT_EQ(RecordSource("no such file.csv").bytes(), 0u);
}

}  // namespace
}  // namespace gyrotherm::studies
