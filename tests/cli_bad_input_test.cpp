// The README's bad-input catalogue, one test per row: the message a user sees
// and exit code 2; the rows that are handled rather than refused (BOM, CRLF,
// gaps, a poorly conditioned design) check that the run works and says so.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <type_traits>

#include "cli_runner.h"
#include "sim/effects/effect.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

// A clean 1 Hz record: a slow temperature cycle from `lo` to `hi` °C and the
// paper's bias on it, with a small deterministic wiggle as noise.
std::string record(double lo = -10.0, double hi = 50.0, int rows = 20000, const std::string& eol = "\n",
                   double gap_from = -1, double gap_to = -1) {
  std::string s = "time_s,temp_c,gyro_dph" + eol;
  for (int k = 0; k < rows; ++k) {
    const double t = k;
    if (t >= gap_from && t < gap_to) continue;
    const double temp = lo + (hi - lo) * 0.5 * (1.0 - std::cos(2.0 * M_PI * t / 20000.0));
    const double rate = (hi - lo) * 0.5 * std::sin(2.0 * M_PI * t / 20000.0) * 2.0 * M_PI / 20000.0;
    const double gyro = -7.0 - 3e-4 * temp + 1e-6 * temp * temp + 1.8 * rate + 0.002 * std::sin(1.7 * k);
    s += std::to_string(t) + "," + std::to_string(temp) + "," + std::to_string(gyro) + eol;
  }
  return s;
}

// A row's file, made when its test runs: the suite's rows are built when the
// program registers its tests, which every test process does (ctest runs
// each test in a process of its own), so a row holds how to make its file.
struct Csv {
  std::function<std::string()> make;
  Csv(const char* text) : make([t = std::string(text)] { return t; }) {}
  template <class F>
    requires std::is_invocable_r_v<std::string, F>
  Csv(F f) : make(std::move(f)) {}
};

struct Row {
  std::string name;
  Csv csv;                // written to d.csv; "<dir>" makes d.csv a folder; "" writes nothing
  std::string args;       // the command line after the program name
  int exit_code;
  std::vector<std::string> fragments;  // in stderr for errors, stdout otherwise
};
void PrintTo(const Row& r, std::ostream* os) { *os << r.name; }

class Catalogue : public ::testing::TestWithParam<Row> {};

TEST_P(Catalogue, MessageAndExitCode) {
  const Row& row = GetParam();
  const std::string csv = row.csv.make();
  ScratchDir dir;
  if (csv == "<dir>")
    std::filesystem::create_directories(dir / "d.csv");
  else if (!csv.empty())
    write_text(dir / "d.csv", csv);
  write_text(dir / "fast.toml",
             "rig = \"" + source_path("scenarios/rig_shield.toml") + "\"\ngyro = \"" +
                 source_path("scenarios/gyro.toml") +
                 "\"\nstart_c = 20.0\n[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_min = 5\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = 90.0\nrate_c_per_min = 20.0\n");
  const auto r = run_cli(dir, row.args);
  EXPECT_EQ(r.exit_code, row.exit_code) << r.err << r.out;
  const std::string& text = row.exit_code == 0 ? r.out : r.err;
  for (const std::string& f : row.fragments)
    EXPECT_NE(text.find(f), std::string::npos) << "output: " << text << "\nmissing: " << f;
  if (row.exit_code == 2) {
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

std::string bom() { return "\xEF\xBB\xBF" + record(); }

INSTANTIATE_TEST_SUITE_P(
    Readme, Catalogue,
    ::testing::Values(
        Row{"file_missing", "", "fit d.csv", 2, {"d.csv: no such file"}},
        Row{"file_unreadable", "<dir>", "fit d.csv", 2, {"d.csv: cannot read: it is a folder"}},
        Row{"empty", "\n", "fit d.csv", 2, {"d.csv: empty file, expected a header line"}},
        Row{"header_only", "time_s,temp_c,gyro_dph\n", "fit d.csv", 2,
            {"d.csv:1: the header is not followed by any data row"}},
        Row{"row_with_another_delimiter", "time_s;temp_c;gyro_dph\n0,1,2\n1,1,2\n", "fit d.csv", 2,
            {"d.csv:2: the row has 1 field, the header (line 1) has 3"}},
        Row{"bom_accepted", bom, "fit d.csv", 0, {"instability (std of 100 s averages)"}},
        Row{"crlf_accepted", [] { return record(-10, 50, 20000, "\r\n"); }, "fit d.csv", 0,
            {"instability (std of 100 s averages)"}},
        Row{"non_numeric_cell", "time_s,temp_c,gyro_dph\n0,20,-7\n1,20.x,-7\n", "fit d.csv", 2,
            {"d.csv:3: column temp_c: '20.x' is not a number"}},
        Row{"nan", "time_s,temp_c,gyro_dph\n0,20,-7\n1,20,NaN\n", "fit d.csv", 2,
            {"d.csv:3: column gyro_dph: 'NaN' is not a finite number"}},
        Row{"inf", "time_s,temp_c,gyro_dph\n0,inf,-7\n1,20,-7\n", "fit d.csv", 2,
            {"d.csv:2: column temp_c: 'inf' is not a finite number"}},
        Row{"duplicate_time", "time_s,temp_c,gyro_dph\n0,20,-7\n1,20,-7\n1,20,-7\n", "fit d.csv", 2,
            {"d.csv:4: column time_s: time 1 is not after 1 on line 3"}},
        Row{"decreasing_time", "time_s,temp_c,gyro_dph\n0,20,-7\n5,20,-7\n4,20,-7\n", "fit d.csv", 2,
            {"d.csv:4: column time_s: time 4 is not after 5 on line 3"}},
        Row{"gaps_reported", [] { return record(-10, 50, 20000, "\n", 8000, 9000); }, "fit d.csv", 0, {"1 gap,"}},
        Row{"single_row", "time_s,temp_c,gyro_dph\n0,20,-7\n", "fit d.csv", 2,
            {"d.csv:2: only 1 data row; at least 2 are needed"}},
        Row{"huge_gyro", "time_s,temp_c,gyro_dph\n0,20,-7\n1,20,1e300\n", "fit d.csv", 2,
            {"d.csv:3: column gyro_dph: 1e+300 °/h is beyond any gyro's range"}},
        Row{"huge_temperature", "time_s,temp_c,gyro_dph\n0,20,-7\n1,5000,-7\n", "fit d.csv", 2,
            {"d.csv:3: column temp_c: 5000 is not a temperature in °C"}},
        Row{"constant_temperature", [] { return record(25, 25); }, "fit d.csv", 2,
            {"the regressor of 'T' is constant"}},
        Row{"constant_gyro",
            [] {
              std::string s = "time_s,temp_c,gyro_dph\n";
              for (int k = 0; k < 3000; ++k) s += std::to_string(k) + "," + std::to_string(20 + 0.01 * k) + ",-7\n";
              return s;
            },
            "fit d.csv", 2, {"the gyro output is constant"}},
        Row{"unknown_term", [] { return record(); }, "fit d.csv --model 'T + T^7'", 2,
            {"unknown term 'T^7' (known terms: " + effects::names() + ")"}},
        Row{"contradictory_options", [] { return record(); }, "fit d.csv --keep-outliers --outlier-threshold 5", 2,
            {"--keep-outliers and --outlier-threshold contradict each other"}},
        Row{"option_not_a_number", [] { return record(); }, "fit d.csv --avg 10s", 2, {"--avg '10s': expected a number"}},
        Row{"option_not_a_whole_number", [] { return record(); }, "fit d.csv --seed -1", 2,
            {"--seed '-1': expected a whole number >= 0"}},
        Row{"chamber_cannot_follow", "", "simulate fast.toml -o x.csv", 2,
            {"fast.toml:8: segment 2: a 20 °C/min ramp up to 90 °C needs at least",
             "the chamber cannot follow the profile; slow it to at most"}},
        Row{"ill_conditioned", [] { return record(20, 20.5); }, "fit d.csv --model 'T + T^2 + T^3 + dT'", 2,
            {"collinear on this data (T, T^2, T^3", "condition number", "wider temperature range"}},
        Row{"poorly_conditioned_warns", [] { return record(20, 25); }, "fit d.csv", 0,
            {"warning: T, T^2 are nearly collinear on this data (condition number"}}),
    [](const auto& param_info) { return param_info.param.name; });

}  // namespace
}  // namespace gyrotherm
