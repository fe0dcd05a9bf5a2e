// Tests for fit/data/measurement.h: every file is written by hand here and every
// expected value is read off the text, never taken from the reader itself.

#include "fit/data/measurement.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <vector>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

namespace fs = std::filesystem;

class MeasurementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           fmt::format("gyrotherm_{}_{}_{}", info->test_suite_name(), info->name(),
                       ::testing::UnitTest::GetInstance()->random_seed());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes the bytes exactly as given (no newline translation).
  fs::path write(const std::string& contents, const std::string& name = "data.csv") const {
    const fs::path path = dir_ / name;
    std::ofstream out(path, std::ios::binary);
    out << contents;
    return path;
  }

  // Reads a file that must be rejected; checks every fragment is in the message.
  static std::string expect_error(const fs::path& path,
                                  std::initializer_list<std::string> fragments,
                                  const ColumnMap& columns = {}) {
    try {
      read_measurement_csv(path, columns);
    } catch (const InputError& e) {
      const std::string message = e.what();
      for (const std::string& fragment : fragments)
        EXPECT_NE(message.find(fragment), std::string::npos)
            << "'" << fragment << "' not in: " << message;
      return message;
    }
    ADD_FAILURE() << path << " was accepted";
    return {};
  }

  fs::path dir_;
};

TEST_F(MeasurementTest, ReadsTheNeededColumnsByNameAndIgnoresTheRest) {
  const fs::path path = write(
      "time_s,chamber_c,temp_c,gyro_dph,note\n"
      "0,20,25.5,-7.25,start\n"
      "1,20.1,25.75,-7.5,\n"
      "2.5,20.2,26,-7.0,x y\n");
  const Measurement m = read_measurement_csv(path);
  EXPECT_EQ(m.file, path.string());
  EXPECT_EQ(m.columns,
            (std::vector<std::string>{"time_s", "chamber_c", "temp_c", "gyro_dph", "note"}));
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m.time_s, (std::vector<double>{0.0, 1.0, 2.5}));
  EXPECT_EQ(m.temp_c, (std::vector<double>{25.5, 25.75, 26.0}));
  EXPECT_EQ(m.gyro_dph, (std::vector<double>{-7.25, -7.5, -7.0}));
  EXPECT_FALSE(m.has_temp2());
  EXPECT_TRUE(m.temp2_c.empty());
}

// The reader's fast path for plain decimals (Clinger's) gives the value
// std::from_chars gives, to the bit, over digits that reach and pass its
// limits (2^53 mantissas, 22 fraction digits, 19 digits in all), signs,
// leading zeros and forms it leaves to from_chars (exponents, '+', "5.", ".5").
TEST_F(MeasurementTest, PlainDecimalsReadAsFromCharsReadsThem) {
  std::vector<std::string> texts = {"0", "-0", "0.0", "-0.000", "1", "-7.000000", "25.56000", "0.1",
                                    "9007199254740992", "9007199254740993", "900719925474099.3",
                                    "0.0000000000000000000001", "0.00000000000000000000012",
                                    "1234567890123456789", "12345678901234567890", "00000000000000000000001.5",
                                    "1e3", "-2.5E-3", "+4.25", "5.", ".5", "3.14159265358979323846"};
  std::uint64_t x = 0x9E3779B97F4A7C15ull;
  for (int k = 0; k < 3000; ++k) {  // random decimals of 1..19 digits, point anywhere
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    const int digits = 1 + static_cast<int>(x % 19);
    std::string d;
    std::uint64_t y = x;
    for (int i = 0; i < digits; ++i, y = y * 6364136223846793005ull + 1442695040888963407ull)
      d += static_cast<char>('0' + (y >> 60) % 10);
    const auto point = static_cast<std::size_t>((x >> 20) % static_cast<std::uint64_t>(digits + 1));
    std::string text = (x >> 40) % 2 ? "-" : "";
    text += point > 0 && point < d.size() ? d.substr(0, point) + "." + d.substr(point) : d;
    texts.push_back(text);
  }
  std::string csv = "time_s,temp_c,gyro_dph,v\n";  // v: read as a number, no range to keep
  for (std::size_t k = 0; k < texts.size(); ++k) csv += fmt::format("{},20,1,{}\n", k, texts[k]);
  ColumnMap columns;
  columns.extra = {"v"};
  const Measurement m = read_measurement_csv(write(csv), columns);
  ASSERT_EQ(m.size(), texts.size());
  for (std::size_t k = 0; k < texts.size(); ++k) {
    std::string_view t = texts[k];
    if (t.front() == '+') t.remove_prefix(1);
    double expected = 0.0;
    std::from_chars(t.data(), t.data() + t.size(), expected);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.extra.at("v")[k]), std::bit_cast<std::uint64_t>(expected)) << texts[k];
  }
}

TEST_F(MeasurementTest, ReadsTheOptionalSecondTemperature) {
  const Measurement m =
      read_measurement_csv(write("time_s,temp_c,temp2_c,gyro_dph\n"
                                 "0,25,24.5,1\n"
                                 "1,26,25.25,2\n"));
  ASSERT_TRUE(m.has_temp2());
  EXPECT_EQ(m.temp2_c, (std::vector<double>{24.5, 25.25}));
}

TEST_F(MeasurementTest, SkipsCommentsBeforeTheHeaderAndBlankLinesAnywhere) {
  const Measurement m =
      read_measurement_csv(write("# gyrotherm simulate: scenario x, seed 1\n"
                                 "#time_s,temp_c,gyro_dph (not the header)\n"
                                 "\n"
                                 "time_s,temp_c,gyro_dph\n"
                                 "0,1,2\n"
                                 "   \n"
                                 "1,3,4\n"
                                 "\n"));
  EXPECT_EQ(m.columns, (std::vector<std::string>{"time_s", "temp_c", "gyro_dph"}));
  EXPECT_EQ(m.time_s, (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(m.gyro_dph, (std::vector<double>{2.0, 4.0}));
}

TEST_F(MeasurementTest, LineNumbersCountCommentsAndBlankLines) {
  const fs::path path = write(
      "# comment\n"               // 1
      "\n"                        // 2
      "time_s,temp_c,gyro_dph\n"  // 3
      "0,1,2\n"                   // 4
      "\n"                        // 5
      "1,1,2\n"                   // 6
      "2,1,abc\n");               // 7
  expect_error(path, {path.string() + ":7: column gyro_dph: 'abc' is not a number"});
}

TEST_F(MeasurementTest, SkipsAUtf8ByteOrderMark) {
  const Measurement m =
      read_measurement_csv(write("\xEF\xBB\xBFtime_s,temp_c,gyro_dph\n0,1,2\n1,1,3\n"));
  ASSERT_EQ(m.columns.size(), 3u);
  EXPECT_EQ(m.columns[0], "time_s");
  EXPECT_EQ(m.time_s, (std::vector<double>{0.0, 1.0}));

  const Measurement commented = read_measurement_csv(
      write("\xEF\xBB\xBF# comment\ntime_s,temp_c,gyro_dph\n0,1,2\n1,1,3\n", "c.csv"));
  EXPECT_EQ(commented.columns[0], "time_s");
}

TEST_F(MeasurementTest, AcceptsCrlfLineEnds) {
  const Measurement m =
      read_measurement_csv(write("# c\r\ntime_s,temp_c,gyro_dph\r\n0,1,2\r\n\r\n1,1.5,3\r\n"));
  EXPECT_EQ(m.columns, (std::vector<std::string>{"time_s", "temp_c", "gyro_dph"}));
  EXPECT_EQ(m.gyro_dph, (std::vector<double>{2.0, 3.0}));  // no '\r' left on the last field
  EXPECT_EQ(m.temp_c, (std::vector<double>{1.0, 1.5}));

  const fs::path bad = write("time_s,temp_c,gyro_dph\r\n0,1,2\r\n1,1,x\r\n", "bad.csv");
  expect_error(bad, {bad.string() + ":3: column gyro_dph: 'x' is not a number"});
}

TEST_F(MeasurementTest, AcceptsALastLineWithoutNewline) {
  const Measurement m = read_measurement_csv(write("time_s,temp_c,gyro_dph\n0,1,2\n1,1,3"));
  EXPECT_EQ(m.gyro_dph, (std::vector<double>{2.0, 3.0}));
}

TEST_F(MeasurementTest, MapsColumnNamesAndTrimsTheHeader) {
  ColumnMap map;
  map.time = "t";
  map.temp = "T_gyro";
  map.gyro = "omega";
  map.temp2 = "T_far";
  const Measurement m =
      read_measurement_csv(write(" omega , t ,T_far,\tT_gyro \n5,0,30,20\n6,10,31,21\n"), map);
  EXPECT_EQ(m.columns, (std::vector<std::string>{"omega", "t", "T_far", "T_gyro"}));
  EXPECT_EQ(m.time_s, (std::vector<double>{0.0, 10.0}));
  EXPECT_EQ(m.temp_c, (std::vector<double>{20.0, 21.0}));
  EXPECT_EQ(m.gyro_dph, (std::vector<double>{5.0, 6.0}));
  EXPECT_EQ(m.temp2_c, (std::vector<double>{30.0, 31.0}));
}

TEST_F(MeasurementTest, NumbersMayHaveSurroundingSpacesAPlusAndExponents) {
  const Measurement m = read_measurement_csv(
      write("time_s,temp_c,gyro_dph\n 1.5 , +2e-1 ,  -3 \n\t2\t,-1.25E+1,+0\n"));
  EXPECT_EQ(m.time_s, (std::vector<double>{1.5, 2.0}));
  EXPECT_EQ(m.temp_c, (std::vector<double>{0.2, -12.5}));
  EXPECT_EQ(m.gyro_dph, (std::vector<double>{-3.0, 0.0}));
}

TEST_F(MeasurementTest, UnneededColumnsMayHoldAnything) {
  const Measurement m = read_measurement_csv(
      write("time_s,status,temp_c,gyro_dph,case_c\n0,nan,1,2,inf\n1,\"a b\",1,3,\n"));
  EXPECT_EQ(m.size(), 2u);
}

TEST_F(MeasurementTest, ANonNumberNamesFileLineAndColumn) {
  const fs::path path = write("time_s,temp_c,gyro_dph\n0,1,2\n1,abc,3\n");
  expect_error(path, {path.string() + ":3:", "column temp_c", "'abc'", "not a number"});
  const fs::path trailing = write("time_s,temp_c,gyro_dph\n0,1,2\n1,2.5x,3\n", "t.csv");
  expect_error(trailing, {":3:", "column temp_c", "'2.5x'", "not a number"});
}

TEST_F(MeasurementTest, NanAndInfinityInANeededColumnAreRejected) {
  for (const char* text : {"nan", "NaN", "inf", "-Inf", "infinity"}) {
    const fs::path path =
        write(fmt::format("time_s,temp_c,gyro_dph\n0,1,2\n1,1,2\n2,1,{}\n", text));
    expect_error(path, {path.string() + ":4:", "column gyro_dph", "not a finite number"});
  }
  const fs::path huge = write("time_s,temp_c,gyro_dph\n0,1e999,2\n1,1,2\n", "huge.csv");
  expect_error(huge, {":2:", "column temp_c", "'1e999'", "out of the range"});
}

TEST_F(MeasurementTest, AnEmptyNeededFieldIsRejected) {
  const fs::path path = write("time_s,temp_c,gyro_dph\n0,1,2\n1, ,3\n");
  expect_error(path, {":3:", "column temp_c", "empty field"});
}

TEST_F(MeasurementTest, EveryRowNeedsAsManyFieldsAsTheHeader) {
  const fs::path fewer = write("# c\ntime_s,temp_c,gyro_dph\n0,1,2\n1,2\n");
  expect_error(fewer, {fewer.string() + ":4:", "2 fields", "header (line 2) has 3"});
  const fs::path more = write("time_s,temp_c,gyro_dph\n0,1,2,9\n1,2,3\n", "more.csv");
  expect_error(more, {":2:", "4 fields", "has 3"});
}

TEST_F(MeasurementTest, TimeMustIncreaseStrictly) {
  const fs::path same = write("time_s,temp_c,gyro_dph\n0,1,2\n1,1,2\n1,1,2\n");
  expect_error(same, {same.string() + ":4:", "column time_s", "time 1 is not after 1 on line 3"});
  const fs::path back = write("time_s,temp_c,gyro_dph\n0,1,2\n1.5,1,2\n\n0.5,1,2\n", "back.csv");
  expect_error(back, {back.string() + ":5:", "time 0.5 is not after 1.5 on line 3"});
}

TEST_F(MeasurementTest, AMissingRequiredColumnListsTheHeaderAndTheOption) {
  const fs::path path = write("time_s,temperature,gyro_dph\n0,1,2\n1,1,2\n");
  expect_error(path, {path.string() + ":1:", "no column 'temp_c'", "time_s, temperature, gyro_dph",
                      "--temp-col"});
  const fs::path no_gyro = write("# c\ntime_s,temp_c,rate\n0,1,2\n1,1,2\n", "g.csv");
  expect_error(no_gyro, {":2:", "no column 'gyro_dph'", "time_s, temp_c, rate", "--gyro-col"});
  const fs::path no_time = write("t,temp_c,gyro_dph\n0,1,2\n1,1,2\n", "t.csv");
  expect_error(no_time, {"no column 'time_s'", "--time-col"});
  ColumnMap map;
  map.gyro = "omega";
  expect_error(no_gyro, {"no column 'omega'", "time_s, temp_c, rate", "--gyro-col"}, map);
}

TEST_F(MeasurementTest, AnExplicitlyMappedSecondTemperatureMustExist) {
  const fs::path path = write("time_s,temp_c,gyro_dph\n0,1,2\n1,1,2\n");
  ColumnMap map;
  map.temp2 = "far_c";
  expect_error(path, {path.string() + ":1:", "no column 'far_c'", "--temp2-col"}, map);
  EXPECT_FALSE(read_measurement_csv(path).has_temp2());  // the default name may be absent
}

TEST_F(MeasurementTest, TheSecondTemperatureCanBeIgnoredOrUsedAsTheFirst) {
  const fs::path path = write("time_s,temp_c,temp2_c,gyro_dph\n0,25,24,1\n1,26,23,2\n");
  ColumnMap ignore;
  ignore.temp2 = "";
  EXPECT_FALSE(read_measurement_csv(path, ignore).has_temp2());
  ColumnMap far_side;  // the far sensor as the main one; temp2 keeps its default name
  far_side.temp = "temp2_c";
  const Measurement m = read_measurement_csv(path, far_side);
  EXPECT_EQ(m.temp_c, (std::vector<double>{24.0, 23.0}));
  EXPECT_FALSE(m.has_temp2());
}

TEST_F(MeasurementTest, DuplicateColumnNamesAreRejected) {
  const fs::path path = write("time_s,temp_c,gyro_dph,temp_c\n0,1,2,3\n1,1,2,3\n");
  expect_error(path, {path.string() + ":1:", "'temp_c' appears twice", "columns 2 and 4"});
}

TEST_F(MeasurementTest, OneColumnCannotPlayTwoRoles) {
  const fs::path path = write("time_s,temp_c,gyro_dph\n0,1,2\n1,1,2\n");
  ColumnMap map;
  map.temp = "gyro_dph";
  expect_error(path, {":1:", "--temp-col and --gyro-col both name column 'gyro_dph'"}, map);
}

// Semicolons and tabs are read by the header's (the forms: tests/csv_dialect_test.cpp).
TEST_F(MeasurementTest, SemicolonAndTabFilesAreReadByTheirHeader) {
  const Measurement plain = read_measurement_csv(write("time_s,temp_c,gyro_dph\n0,1,2\n1,1,3\n", "p.csv"));
  for (const char* text : {"time_s;temp_c;gyro_dph\n0;1;2\n1;1;3\n", "# c\ntime_s\ttemp_c\tgyro_dph\n0\t1\t2\n1\t1\t3\n"}) {
    const Measurement m = read_measurement_csv(write(text, "d.csv"));
    EXPECT_EQ(m.columns, plain.columns);
    EXPECT_EQ(m.gyro_dph, plain.gyro_dph);
  }
  // A row that keeps the comma where the header has semicolons is one field short.
  expect_error(write("time_s;temp_c;gyro_dph\n0,1,2\n", "m.csv"), {"m.csv:2:", "the row has 1 field, the header (line 1) has 3"});
}

TEST_F(MeasurementTest, FilesWithoutEnoughDataAreRejected) {
  const fs::path empty = write("", "empty.csv");
  expect_error(empty, {empty.string() + ":", "empty file", "time_s, temp_c, gyro_dph"});
  const fs::path blank = write("\n  \n", "blank.csv");
  expect_error(blank, {"empty file"});
  const fs::path comments = write("# only\n# comments\n", "comments.csv");
  expect_error(comments, {"no header"});
  const fs::path header = write("# c\ntime_s,temp_c,gyro_dph\n\n", "header.csv");
  expect_error(header, {header.string() + ":2:", "not followed by any data row"});
  const fs::path one = write("time_s,temp_c,gyro_dph\n0,1,2\n", "one.csv");
  expect_error(one, {one.string() + ":2:", "only 1 data row", "at least 2"});
}

TEST_F(MeasurementTest, MissingAndUnreadableFilesAreNamed) {
  const fs::path missing = dir_ / "nowhere.csv";
  expect_error(missing, {missing.string() + ": no such file"});
  expect_error(dir_, {dir_.string() + ": cannot read"});
}

TEST_F(MeasurementTest, ALineLongerThanTheReadBlockIsReadWhole) {
  const std::string note(3u << 20, 'x');  // 3 MiB, longer than the 1 MiB block
  const Measurement m = read_measurement_csv(
      write("time_s,note,temp_c,gyro_dph\n0," + note + ",1,2\n1," + note + ",3,4\n2,y,5,6\n"));
  EXPECT_EQ(m.time_s, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_EQ(m.gyro_dph, (std::vector<double>{2.0, 4.0, 6.0}));
}

// A day-long 1 Hz record of 10⁵ rows, in the simulator's layout. The expected
// values are parsed from the same text with std::strtod, a different parser.
TEST_F(MeasurementTest, ReadsBackA100kRowRecord) {
  constexpr std::size_t kRows = 100000;
  std::string text =
      "# gyrotherm simulate: scenario long, seed 7\n"
      "time_s,chamber_c,case_c,temp_c,temp2_c,gyro_dph,bias_true_dph\n";
  std::vector<std::string> temp_text(kRows), gyro_text(kRows);
  for (std::size_t k = 0; k < kRows; ++k) {
    const double t = static_cast<double>(k);
    temp_text[k] = fmt::format("{:.5f}", 20.0 + 30.0 * std::sin(t / 8000.0));
    gyro_text[k] = fmt::format("{:.6f}", -7.0 + 0.05 * static_cast<double>(k % 7) - 0.1);
    text += fmt::format("{},{:.5f},{:.5f},{},{:.5f},{},{:.9f}\n", k, 1.0, 2.0, temp_text[k],
                        3.0 + t * 1e-4, gyro_text[k], -7.0);
  }
  const fs::path path = write(text);

  const auto start = std::chrono::steady_clock::now();
  const Measurement m = read_measurement_csv(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("megabytes_per_second",
                 fmt::format("{:.0f}", static_cast<double>(text.size()) / 1e6 / seconds));

  ASSERT_EQ(m.size(), kRows);
  ASSERT_TRUE(m.has_temp2());
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < kRows; ++k) {
    mismatches += m.time_s[k] != static_cast<double>(k);
    mismatches += m.temp_c[k] != std::strtod(temp_text[k].c_str(), nullptr);
    mismatches += m.gyro_dph[k] != std::strtod(gyro_text[k].c_str(), nullptr);
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_DOUBLE_EQ(m.temp2_c.back(), 3.0 + 99999e-4);
}

// Units: each conversion by hand, then a raw log read with them.
TEST(Units, ConvertToSecondsDegreesCelsiusAndDegreesPerHour) {
  Units u;
  EXPECT_TRUE(u.identity());
  EXPECT_EQ(u.description(), "none");
  u.time = "ms";
  EXPECT_DOUBLE_EQ(u.time_s(1500.0), 1.5);
  u.time = "us";
  EXPECT_DOUBLE_EQ(u.time_s(2.0e6), 2.0);
  u.gyro = "dps";
  EXPECT_DOUBLE_EQ(u.gyro_dph(1.0), 3600.0);
  u.gyro = "mdps";
  EXPECT_DOUBLE_EQ(u.gyro_dph(1000.0), 3600.0);
  u.gyro = "rad/s";
  u.gyro_scale = 0.5;  // the PAN logger's factor 2
  EXPECT_NEAR(u.gyro_dph(1.0), 0.5 * 206264.80624709636, 1e-9);
  u.temp = "K";
  EXPECT_NEAR(u.temp_c(300.0), 26.85, 1e-12);
  u.temp = "F";
  EXPECT_NEAR(u.temp_c(212.0), 100.0, 1e-12);
  u.temp = "C";
  u.temp_scale = 1.0 / 256.0;
  u.temp_offset = -231.0;
  EXPECT_DOUBLE_EQ(u.temp_c(65236.0), 65236.0 / 256.0 - 231.0);
  EXPECT_NE(u.description().find("0.00390625 × column − 231 → °C"), std::string::npos) << u.description();
}

TEST(Units, BadUnitsAndScalesAreNamed) {
  for (const auto& [units, fragment] : std::vector<std::pair<Units, std::string>>{
           {Units{.time = "fortnight"}, "--time-unit fortnight: unknown unit (expected one of s, ms, us, ns, min, h)"},
           {Units{.gyro = "deg/hr"}, "--gyro-unit deg/hr: unknown unit"},
           {Units{.temp = "R"}, "--temp-unit R: unknown unit (expected one of C, K, F)"},
           {Units{.gyro_scale = 0.0}, "--gyro-scale 0: must be a finite number other than 0"},
           {Units{.temp_scale = std::nan("")}, "--temp-scale nan"}}) {
    try {
      units.validate();
      ADD_FAILURE() << fragment;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  }
}

TEST_F(MeasurementTest, ReadsARawLogInItsOwnUnits) {
  const fs::path raw = write("time (ms),g rad/s,temp\n1000,1e-3,65236\n1020,2e-3,65237\n");
  ColumnMap columns{.time = "time (ms)", .temp = "temp", .gyro = "g rad/s"};
  columns.units = Units{.time = "ms", .gyro = "rad/s", .temp_scale = 1.0 / 256.0, .temp_offset = -231.0};
  const Measurement m = read_measurement_csv(raw, columns);
  EXPECT_DOUBLE_EQ(m.time_s[1], 1.02);
  EXPECT_NEAR(m.gyro_dph[0], 206.26480624709636, 1e-9);
  EXPECT_DOUBLE_EQ(m.temp_c[1], 65237.0 / 256.0 - 231.0);
  // Without the temperature conversion the counts are no temperature, and the
  // message says so.
  columns.units.temp_scale = 1.0;
  columns.units.temp_offset = 0.0;
  expect_error(raw, {"column temp: 65236 is not a temperature in °C"}, columns);
  // A range error after a conversion names it.
  columns.units.temp = "K";
  expect_error(raw, {"converted by", "temp column in K → °C"}, columns);
}


// As pandas (QUOTE_NONNUMERIC, QUOTE_ALL) and spreadsheets write a CSV: the
// quoted names and numbers read as the plain file does.
TEST_F(MeasurementTest, QuotedNamesAndNumbersReadAsPlainOnes) {
  const Measurement plain = read_measurement_csv(write("time_s,temp_c,gyro_dph,note\n0,20.5,1.25,x\n1,20.6,1.5,y\n", "p.csv"));
  const Measurement names = read_measurement_csv(
      write("\"time_s\",\"temp_c\",\"gyro_dph\",\"note\"\n0,20.5,1.25,\"x\"\n1,20.6,1.5,\"y\"\n", "n.csv"));
  const Measurement all = read_measurement_csv(
      write("\"time_s\",\"temp_c\",\"gyro_dph\",\"note\"\r\n\"0\",\"20.5\",\" 1.25 \",\"x\"\r\n\"1\",\"20.6\",\"1.5\",\"y\"\r\n", "a.csv"));
  for (const Measurement* m : {&names, &all}) {
    EXPECT_EQ(m->columns, plain.columns);
    EXPECT_EQ(m->time_s, plain.time_s);
    EXPECT_EQ(m->temp_c, plain.temp_c);
    EXPECT_EQ(m->gyro_dph, plain.gyro_dph);
  }
  // A quote inside a quoted name is doubled; an empty quoted number is still no number.
  ColumnMap odd;
  odd.gyro = "gyro \"x\"";
  EXPECT_EQ(read_measurement_csv(write("time_s,temp_c,\"gyro \"\"x\"\"\"\n0,20,1\n1,20,2\n", "q.csv"), odd).gyro_dph,
            (std::vector<double>{1.0, 2.0}));
  expect_error(write("time_s,temp_c,gyro_dph\n0,20,\"\"\n1,20,2\n", "e.csv"), {":2: column gyro_dph: empty field"});
}

}  // namespace
}  // namespace gyrotherm::fit
