// CSV as spreadsheets and loggers write it (fit/data/csv_dialect.h): fields
// split outside quotes, decimal commas, ISO 8601 timestamps, the delimiter
// from the header; a record written in each form gives the plain CSV's fit
// bit for bit, and each form's mistakes stop with the line and the option.

#include "fit/data/csv_dialect.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "expect_input_error.h"
#include "synthetic_log.h"

namespace gyrotherm::fit {
namespace {

using testing::expect_input_error;
using testing::expect_refused;
using testing::fit_json;
using testing::run_cli;
using testing::ScratchDir;
using testing::write_text;

std::vector<std::string> split(std::string_view line, char d) {
  std::vector<std::string_view> fields;
  EXPECT_EQ(split_fields(line, d, fields), "") << line;
  return {fields.begin(), fields.end()};
}

TEST(CsvDialect, FieldsAreSplitOutsideQuotes) {
  using V = std::vector<std::string>;
  EXPECT_EQ(split("0,20.5,1", ','), (V{"0", "20.5", "1"}));
  EXPECT_EQ(split("0;20,5;1", ';'), (V{"0", "20,5", "1"}));
  EXPECT_EQ(split("0\t\t1", '\t'), (V{"0", "", "1"}));
  EXPECT_EQ(split("0,\"a, b\",\"say \"\"hi, there\"\"\",2", ','),
            (V{"0", "\"a, b\"", "\"say \"\"hi, there\"\"\"", "2"}));
  std::vector<std::string_view> fields;
  EXPECT_NE(split_fields("0,\"open,2", ',', fields).find("field 2 opens a quote"), std::string::npos);
  EXPECT_EQ(unquote_field(" \"say \"\"hi\"\"\" "), "say \"hi\"");
}

TEST(CsvDialect, DecimalCommasReadAsTheirPointedTwins) {
  double v = 0.0, w = 0.0;
  for (const char* text : {"20,5", "-0,125", "1,5e-3", "\"3,25\"", " +7,0 "}) {
    std::string pointed = text;
    for (char& c : pointed)
      if (c == ',') c = '.';
    ASSERT_EQ(parse_csv_number(text, true, v), "") << text;
    ASSERT_EQ(parse_csv_number(pointed, false, w), "") << pointed;
    EXPECT_EQ(v, w) << text;
  }
  // Beside decimal commas a '.' separates thousands ("1.234" is 1234): refused, not misread.
  for (const char* text : {"1.234", "1.234,5", "2.5"})
    EXPECT_NE(parse_csv_number(text, true, v).find("a thousands separator?"), std::string::npos) << text;
  // A long field reads whole (no fixed buffer).
  ASSERT_EQ(parse_csv_number("0,000000000000000000000000000000000000000000000000000000000000000000000012", true, v), "");
  EXPECT_DOUBLE_EQ(v, 1.2e-71);
  // Without the option a decimal comma is no number, and the message says which option reads it.
  EXPECT_NE(parse_csv_number("20,5", false, v).find("give --decimal-comma"), std::string::npos);
}

// A field of the kinds data rows hold, and of the kinds the fast path leaves
// to the general one: numbers in every notation, quotes, blanks, text, the delimiters.
std::string random_field(std::mt19937_64& rng) {
  static const std::vector<std::string> pieces = {
      "0",    "7",    "-",    "+",     ".",     ",",    "e",   "E-",  "e+0", "05",  "123456789", "9999999999",
      "\"",  " ",    "\t",  ";",     "nan",   "inf",  "x",   "1e30", "2026-11-26T05:38:35.25Z", "00000"};
  std::uniform_int_distribution<std::size_t> pick(0, pieces.size() - 1), count(0, 5);
  std::string out;
  for (std::size_t k = count(rng); k > 0; --k) out += pieces[pick(rng)];
  return out;
}

// Whatever a line holds, the fast path (scan_csv_number, skip_csv_field,
// scan_iso8601_field) takes a field only where split_fields finds the same
// field and parse_csv_number (or parse_iso8601 of unquote_field) the same
// number, to the bit.
TEST(CsvDialect, TheFastPathReadsWhatTheGeneralOneReads) {
  std::mt19937_64 rng(11);
  std::size_t taken = 0, left = 0;
  for (int line_number = 0; line_number < 60000; ++line_number) {
    const char delimiter = ",;\t"[line_number % 3];
    const bool comma = delimiter != ',' && line_number % 2 == 0;
    std::string line = random_field(rng);
    for (int k = 0; k < 3; ++k) line += delimiter + random_field(rng);
    std::vector<std::string_view> fields;
    const char* p = line.data();
    const char* const end = p + line.size();
    if (!split_fields(line, delimiter, fields).empty()) {  // a quote left open: the fast path stops somewhere too
      for (p = skip_csv_field(p, end, delimiter); p != nullptr && p != end;) p = skip_csv_field(p + 1, end, delimiter);
      EXPECT_EQ(p, nullptr) << line;
      continue;
    }
    for (std::size_t f = 0;; ++f) {
      const char* start = p;
      double value = 0.0, expected = 0.0;
      Timestamp t, u;
      const char* number = scan_csv_number(start, end, delimiter, comma, value);
      const char* iso = scan_iso8601_field(start, end, delimiter, t);
      p = skip_csv_field(start, end, delimiter);
      ASSERT_NE(p, nullptr) << line;
      ASSERT_LT(f, fields.size()) << line;
      ASSERT_EQ(std::string_view(start, static_cast<std::size_t>(p - start)), fields[f]) << line;
      if (number != nullptr) {
        ++taken;
        ASSERT_EQ(number, p) << line;
        ASSERT_EQ(parse_csv_number(fields[f], comma, expected), "") << fields[f];
        EXPECT_EQ(std::signbit(value), std::signbit(expected)) << fields[f];
        EXPECT_EQ(value, expected) << fields[f];
      } else {
        ++left;
      }
      if (iso != nullptr) {
        ASSERT_EQ(iso, p);
        ASSERT_TRUE(parse_iso8601(unquote_field(fields[f]), u)) << fields[f];
        EXPECT_EQ(t.seconds, u.seconds);
        EXPECT_EQ(t.fraction, u.fraction);
      }
      if (p == end) {
        EXPECT_EQ(f + 1, fields.size()) << line;
        break;
      }
      ++p;
    }
  }
  EXPECT_GT(taken, 10000u);
  EXPECT_GT(left, 10000u);
}

TEST(CsvDialect, TheFastPathTakesTheUsualNumbers) {
  double v = 0.0;
  for (const auto& [text, expected] : std::vector<std::pair<std::string, double>>{
           {"20.5", 20.5}, {" -0.125 ", -0.125}, {"\"3.25\"", 3.25}, {" \" 7 \" ", 7.0}, {"6.78739e-05", 6.78739e-05},
           {"1E3", 1e3}, {"-2.5e+2", -250.0}, {"9007199254740992", 9007199254740992.0}}) {
    const char* end = text.data() + text.size();
    ASSERT_EQ(scan_csv_number(text.data(), end, ',', false, v), end) << text;
    EXPECT_EQ(v, expected) << text;
  }
  const std::string comma = "-20,5;";
  ASSERT_EQ(scan_csv_number(comma.data(), comma.data() + comma.size(), ';', true, v), comma.data() + 5);
  EXPECT_EQ(v, -20.5);
  for (const std::string text : {"+1", "1.", ".5", "1e", "1e400", "12345678901234567890", "1.5x", "\"1", "0x10", ""}) {
    const char* end = text.data() + text.size();
    EXPECT_EQ(scan_csv_number(text.data(), end, ',', false, v), nullptr) << text;
  }
}

TEST(CsvDialect, Iso8601TimestampsAreUtcSeconds) {
  Timestamp t;
  ASSERT_TRUE(parse_iso8601("1970-01-01T00:00:00Z", t));
  EXPECT_EQ(t.seconds, 0);
  ASSERT_TRUE(parse_iso8601("2026-11-26T05:38:35.25Z", t));
  EXPECT_EQ(t.seconds, 1795671515);  // date -d 2026-11-26T05:38:35Z +%s
  EXPECT_EQ(t.fraction, 0.25);
  Timestamp local;
  ASSERT_TRUE(parse_iso8601("2026-11-26 06:38:35.25+01:00", local));
  EXPECT_EQ(local.seconds, t.seconds);
  ASSERT_TRUE(parse_iso8601("2026-11-26T00:08:35.25-0530", local));
  EXPECT_EQ(local.seconds, t.seconds);
  ASSERT_TRUE(parse_iso8601("2024-02-29T12:00", t));  // a leap day; no seconds: :00
  EXPECT_EQ(t.seconds, 1709208000);
  for (const char* bad : {"2023-02-29T12:00:00Z", "2026-13-01T00:00:00Z", "2026-11-26T24:00:00Z",
                          "2026-11-26T12:00:60Z", "2026-11-26T05:38:35+01:",
                          "2026-11-26T05:38:35.Z", "2026-11-26", "2026-11-26T05:38:35Q", "20261126T053835Z",
                          "12.5"})
    EXPECT_FALSE(parse_iso8601(bad, t)) << bad;
}

TEST(CsvDialect, TheDelimiterComesFromTheHeaderUnlessGiven) {
  CsvDialect d;
  EXPECT_EQ(d.delimiter_for("time_s,temp_c,gyro_dph"), ',');
  EXPECT_EQ(d.delimiter_for("time_s;temp_c;gyro_dph"), ';');
  EXPECT_EQ(d.delimiter_for("time_s\ttemp_c\tgyro_dph"), '\t');
  EXPECT_EQ(d.delimiter_for("time;temp;gyro (x,y)"), ';');        // the one used most
  EXPECT_EQ(d.delimiter_for("\"a;b\",\"c;d\",e"), ',');           // not inside quotes
  d.delimiter = "tab";
  EXPECT_EQ(d.delimiter_for("time_s,temp_c"), '\t');
  d.delimiter = ";";
  EXPECT_EQ(d.describe(d.delimiter_for("a,b")), "semicolon-separated");
  d.decimal_comma = true;
  EXPECT_EQ(d.describe(';'), "semicolon-separated, decimal comma");
  d.delimiter = "comma";  // decimal commas in quotes between comma delimiters (RFC 4180)
  EXPECT_EQ(d.delimiter_for("a;b"), ',');
  d.delimiter = "pipe";
  expect_input_error([&] { d.validate(); }, {"--delimiter 'pipe'", "comma, semicolon, tab or auto"});
  d.delimiter = "auto";
  d.rate_hz = -1.0;
  expect_input_error([&] { d.validate(); }, {"--rate -1", "> 0"});
}

// A row's decimal points as decimal commas.
std::string commas(std::string row) {
  std::replace(row.begin(), row.end(), '.', ',');
  return row;
}

// The synthetic log written as spreadsheets and loggers write it, each form's
// fit equal to the plain CSV's to the last bit (the numbers read are the same).
TEST(CsvDialect, ARecordWrittenInEachFormGivesThePlainFit) {
  ScratchDir dir;
  struct Form {
    std::string file, header, options;
    std::string (*row)(const testing::LogRow&);
  };
  const std::vector<Form> forms = {
      {"plain.csv", "time_s,temp_c,gyro_dph", "",
       [](const testing::LogRow& r) { return fmt::format("{:.17g},{:.17g},{:.17g}", r.t, r.temp_c, r.gyro_dph); }},
      {"excel.csv", "time_s;temp_c;gyro_dph", "--decimal-comma",
       [](const testing::LogRow& r) { return commas(fmt::format("{:.17g};{:.17g};{:.17g}", r.t, r.temp_c, r.gyro_dph)); }},
      {"quoted_commas.csv", "time_s,temp_c,gyro_dph", "--decimal-comma",  // RFC 4180 quotes around decimal commas
       [](const testing::LogRow& r) {
         return commas(fmt::format("\"{:.17g}\",\"{:.17g}\",\"{:.17g}\"", r.t, r.temp_c, r.gyro_dph));
       }},
      {"tabs.tsv", "\"time_s\"\t\"temp_c\"\t\"gyro_dph\"", "--delimiter tab",
       [](const testing::LogRow& r) { return fmt::format("{:.17g}\t{:.17g}\t{:.17g}", r.t, r.temp_c, r.gyro_dph); }},
      {"quoted.csv", "time_s,\"note, free\",temp_c,gyro_dph", "",
       [](const testing::LogRow& r) {
         return fmt::format("{:.17g},\"ok, \"\"fine\"\"\",\"{:.17g}\",{:.17g}", r.t, r.temp_c, r.gyro_dph);
       }},
      {"iso.csv", "timestamp,temp_c,gyro_dph", "--time-col timestamp",
       [](const testing::LogRow& r) {
         const auto s = static_cast<int>(r.t);  // from 2026-11-26T23:00:00+01:00, across midnight
         return fmt::format("2026-11-{:02d}T{:02d}:{:02d}:{:02d}.000+01:00,{:.17g},{:.17g}", 26 + (23 + s / 3600) / 24,
                            (23 + s / 3600) % 24, s / 60 % 60, s % 60, r.temp_c, r.gyro_dph);
       }},
      {"serial.csv", "temp_c,gyro_dph", "--rate 1",
       [](const testing::LogRow& r) { return fmt::format("{:.17g},{:.17g}", r.temp_c, r.gyro_dph); }},
  };
  nlohmann::json plain;
  for (const Form& form : forms) {
    std::string text = form.header + "\r\n";
    for (const testing::LogRow& r : testing::synthetic_log()) text += form.row(r) + "\r\n";
    write_text(dir / form.file, text);
    const nlohmann::json j = fit_json(dir, form.file + " " + form.options);
    ASSERT_FALSE(j.is_null()) << form.file;
    if (plain.is_null()) plain = j;
    EXPECT_EQ(j["coefficients"], plain["coefficients"]) << form.file;
    EXPECT_EQ(j["instability_after_dph"], plain["instability_after_dph"]) << form.file;
    EXPECT_EQ(j["data"]["windows"], plain["data"]["windows"]) << form.file;
  }
  // Each report says how the file was read; the fit file keeps the options,
  // so compensate reads the same file again without them.
  const nlohmann::json excel = fit_json(dir, "excel.csv --decimal-comma -o excel.json");
  EXPECT_NE(excel["data"]["units"].get<std::string>().find("semicolon-separated, decimal comma"), std::string::npos)
      << excel["data"]["units"];
  EXPECT_EQ(excel["pipeline"]["columns"]["csv"]["decimal_comma"], true);
  EXPECT_EQ(run_cli(dir, "compensate --fit excel.json excel.csv -o out.csv").exit_code, 0);
  const nlohmann::json iso = fit_json(dir, "iso.csv --time-col timestamp");
  EXPECT_NE(iso["data"]["units"].get<std::string>().find("ISO 8601 timestamps, s since 2026-11-26T23:00:00.000+01:00"),
            std::string::npos)
      << iso["data"]["units"];
  const nlohmann::json serial = fit_json(dir, "serial.csv --rate 1");
  EXPECT_NE(serial["data"]["units"].get<std::string>().find("--rate 1 Hz, no time column"), std::string::npos);
}

TEST(CsvDialect, EachFormsMistakesNameTheLineAndTheOption) {
  ScratchDir dir;
  const std::vector<std::pair<std::string, std::string>> files = {
      {"comma.csv", "time_s;temp_c;gyro_dph\n0;20,5;1\n1;20,6;2\n"},
      {"open.csv", "time_s,temp_c,gyro_dph\n0,\"20.5,1\n1,20.6,2\n"},
      {"unquoted.csv", "time_s,temp_c,gyro_dph\n0,20,5,1\n1,\"20,6\",2\n"},
      {"mixed.csv", "t,temp_c,gyro_dph\n2026-11-26T00:00:00Z,20,1\n2026-11-26T00:00:01Z,20,1\n1.5,20,1\n"},
      {"back.csv", "t,temp_c,gyro_dph\n2026-11-26T00:00:01Z,20,1\n2026-11-26T01:00:00+01:00,20,1\n"},
      {"timed.csv", "time_s,temp_c,gyro_dph\n0,20,1\n1,20,1\n"},
      {"serial.csv", "temp_c,gyro_dph\n20,1\n20,1\n"}};
  for (const auto& [name, text] : files) write_text(dir / name, text);
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"comma.csv", "comma.csv:2: column temp_c: '20,5' is not a number (a decimal comma? give --decimal-comma)"},
      {"unquoted.csv --decimal-comma",
       "unquoted.csv:2: the row has 4 fields, the header (line 1) has 3 (with --decimal-comma in a comma-separated "
       "file, a number with a decimal comma must be in quotes"},
      {"comma.csv --delimiter pipe", "--delimiter 'pipe'"},
      {"open.csv", "open.csv:2: field 2 opens a quote that the line does not close"},
      {"mixed.csv --time-col t", "mixed.csv:4: column t: '1.5' is not an ISO 8601 timestamp"},
      {"mixed.csv --time-col t --time-unit ms", "is an ISO 8601 timestamp, but --time-unit gives the time unit ms"},
      {"back.csv --time-col t", "time -1 is not after 0 on line 2 (time must be strictly increasing; read as seconds "
                                "since the first row's timestamp)"},
      {"timed.csv --rate 10", "--rate 10 Hz is for a log without a time column, but column 'time_s' holds the time"},
      {"serial.csv --rate 10 --time-unit ms", "--time-unit gives the time unit ms, but with --rate there is no time column"},
      {"serial.csv --rate 0", "no column 'time_s'"}};
  for (const auto& [args, expected] : refused) expect_refused(dir, "fit " + args, expected);
}

// A name that differs from a column only in case or separators is offered.
TEST(CsvDialect, ANameThatDiffersInCaseOrSeparatorsIsOffered) {
  ScratchDir dir;
  write_text(dir / "caps.csv", "Time S,Temp-C,GYRO_DPH\n0,20,1\n1,20,2\n");
  expect_refused(dir, "fit caps.csv", "no column 'time_s' (did you mean 'Time S'?)");
  expect_refused(dir, "fit caps.csv --time-col 'Time S'", "no column 'temp_c' (did you mean 'Temp-C'?)");
  expect_refused(dir, "fit caps.csv --time-col 'Time S' --temp-col Temp-C", "did you mean 'GYRO_DPH'?");
  expect_refused(dir, "fit caps.csv --time-col clock", "no column 'clock' (the header has:");
}

// UTF-16 text (a spreadsheet's "Unicode text"), with and without a
// byte-order mark: named as such, with the conversion to make, by every
// command that reads a record.
TEST(CsvDialect, Utf16TextIsNamedWithTheConversion) {
  ScratchDir dir;
  const std::string text = "time_s,temp_c,gyro_dph\n0,20,1\n1,20,2\n";
  std::string le = "\xFF\xFE", be = "\xFE\xFF", bare;
  for (char c : text) {
    le += std::string{c, '\0'};
    be += std::string{'\0', c};
    bare += std::string{c, '\0'};
  }
  write_text(dir / "le.csv", le);
  write_text(dir / "be.csv", be);
  write_text(dir / "bare.csv", bare);
  for (const std::string command : {"fit", "diagnose", "allan"}) {
    expect_refused(dir, command + " le.csv", "le.csv:1: the file is UTF-16 text (byte-order mark FF FE, little-endian)");
    expect_refused(dir, command + " be.csv", "be.csv:1: the file is UTF-16 text (byte-order mark FE FF, big-endian)");
    expect_refused(dir, command + " bare.csv", "iconv -f UTF-16 -t UTF-8 bare.csv > converted.csv");
  }
}

}  // namespace
}  // namespace gyrotherm::fit
