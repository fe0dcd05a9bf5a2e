// `gyrotherm diagnose` end to end: the JSON contract, the walk-through of the
// README (simulate with a hidden gradient, diagnose, add it), the plots, and
// bad input.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <regex>

#include "cli_runner.h"
#include "sim/effects/effect.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

// A 4 h record at 1 Hz whose temperature creeps 0.6 °C (13.0 to 13.6 °C), with
// a bias of 2 °/h/°C and white noise: temperature bands far narrower than 1 °C.
// A second channel, gyro2_dph, holds −1 °/h/°C and its own white noise.
void write_narrow_record(const std::filesystem::path& csv) {
  write_ramp_log(csv, "gyro_dph,gyro2_dph", {2.0, -1.0}, 4.0, 13.0, 13.6, 7);
}

// Every "A..B °C" or "A .. B °C" in a report, as printed.
std::vector<std::pair<std::string, std::string>> printed_ranges(const std::string& text) {
  static const std::regex range(R"((-?[0-9]+(?:\.[0-9]+)?) ?\.\. *(-?[0-9]+(?:\.[0-9]+)?) °C)");
  std::vector<std::pair<std::string, std::string>> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), range); it != std::sregex_iterator(); ++it)
    out.emplace_back((*it)[1], (*it)[2]);
  return out;
}

// A hidden gradient (the second temperature logged) on the cycle, a random
// profile and a bursty copy of the cycle: grad is named first, or first
// together with the terms this record cannot tell it from; the fitted lag
// filter, which can mimic it, is never significant alone.
TEST(CliDiagnose, AHiddenGradientIsNamedFirstOrGroupedNeverTheLagAlone) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "--hidden grad=0.0533 --seed 3", "cycle.csv");
  simulate_shipped(dir, "random", "--hidden grad=0.0533 --seed 3", "random.csv");
  {
    std::ifstream in(dir / "cycle.csv");
    std::ofstream out(dir / "bursts.csv");
    for (std::string line; std::getline(in, line);)
      if (line.empty() || line[0] == '#' || line.rfind("time_s", 0) == 0 ||
          std::fmod(std::stod(line.substr(0, line.find(','))), 300.0) < 60.0)
        out << line << "\n";
  }
  for (const char* csv : {"cycle.csv", "random.csv", "bursts.csv"}) {
    const auto r = run_cli(dir, std::string("diagnose ") + csv + " --json");
    ASSERT_EQ(r.exit_code, 0) << csv << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const auto& first = j["missing_effects"][0];
    const auto& with = first["confounded_with"];
    const bool grouped = std::find(with.begin(), with.end(), "grad") != with.end();
    EXPECT_TRUE(first["term"] == "grad" || grouped) << csv << ": " << j["verdict"];
    EXPECT_TRUE(first["significant"].get<bool>() || first["group_significant"].get<bool>()) << csv;
    for (const auto& c : j["missing_effects"]) {
      if (c["term"] == "lag") {
        EXPECT_FALSE(c["significant"].get<bool>()) << csv << ": " << j["verdict"];
      }
    }
  }
}

TEST(CliDiagnose, FindsAHiddenGradientAndWatchesTheErrorFall) {
  ScratchDir dir;
  ASSERT_EQ(run_cli(dir, "simulate " + source_path("scenarios/cycle.toml") +
                             " --hidden grad=0.0533 -o grad.csv")
                .exit_code,
            0);
  const auto r = run_cli(dir, "diagnose grad.csv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"model", "instability_dph", "noise_floor_dph", "segments",
                          "missing_effects", "verdict"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["missing_effects"][0]["term"], "grad");
  EXPECT_TRUE(j["missing_effects"][0]["significant"].get<bool>());
  EXPECT_FALSE(j["missing_effects"][0]["meaning"].get<std::string>().empty());
  for (const char* key : {"kind", "start_s", "end_s", "rms_dph", "ratio_to_floor"})
    EXPECT_TRUE(j["segments"][0].contains(key)) << key;
  // Worst first.
  EXPECT_GE(j["segments"][0]["ratio_to_floor"].get<double>(),
            j["segments"][1]["ratio_to_floor"].get<double>());
  EXPECT_NE(j["next_command"].get<std::string>().find("--model \"T + T^2 + dT + grad\""),
            std::string::npos);

  const auto human = run_cli(dir, "diagnose grad.csv --add grad --plots figs");
  ASSERT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("5. before/after adding grad"), std::string::npos) << human.out;
  EXPECT_NE(human.out.find("verdict:"), std::string::npos);
  for (const char* png : {"bias_time.png", "residual_segments.png", "residual_vs.png",
                          "before_after.png", "allan.png"})
    EXPECT_GT(std::filesystem::file_size(dir / "figs" / png), 10000u) << png;
}

TEST(CliDiagnose, CleanDataSaysSo) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "clean.csv");
  const auto r = run_cli(dir, "diagnose clean.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("no missing effect is significant"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("next:"), std::string::npos);
}

// A group told apart by no test over the record's range (powers of T nearly
// proportional over it): the plan command leaves --range to the user's
// chamber instead of repeating the record's, and plan --separate on the
// JSON does not take that range either.
TEST(CliDiagnose, APlanForAGroupTheRangeCannotSeparateLeavesTheRangeToTheChamber) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "--hidden T^3=1e-6", "t3.csv");
  const auto text = run_cli(dir, "diagnose t3.csv");
  const auto j = nlohmann::json::parse(run_cli(dir, "diagnose t3.csv --json").out);
  ASSERT_TRUE(j.contains("plan")) << j["verdict"];
  EXPECT_EQ(j["plan"]["range_separates"], false) << j["confounded"];
  EXPECT_EQ(j["plan_command"].get<std::string>().find("--range"), std::string::npos) << j["plan_command"];
  EXPECT_NE(text.out.find("add --range LO,HI, your chamber's, wider than the record's"), std::string::npos) << text.out;
}

// T and a lagged temperature confounded: the record's rates, not its range,
// decide (a lag differs from T by about τ·dT/dt), and the advice says so.
TEST(CliDiagnose, ALagConfoundedWithTemperatureIsToldApartByFasterRampsNotARange) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  const auto j = nlohmann::json::parse(run_cli(dir, "diagnose c.csv --json").out);
  bool seen = false;
  for (const auto& g : j["confounded_groups"]) {
    const auto& m = g["members"];
    if (std::find(m.begin(), m.end(), "lag") == m.end()) continue;
    seen = true;
    ASSERT_EQ(g["evidence"][0]["reason"], "lag_follows_temperature") << g;
    const double fastest = g["evidence"][0]["fastest_rate_c_per_min"].get<double>();
    EXPECT_GT(fastest, 0.1) << g;  // the cycle ramps at 1 °C/min and less
    EXPECT_LT(fastest, 5.0) << g;
    EXPECT_NE(g["text"].get<std::string>().find("faster ramps"), std::string::npos) << g;
    EXPECT_EQ(g["text"].get<std::string>().find("wider temperature range"), std::string::npos) << g;
  }
  EXPECT_TRUE(seen) << j["confounded_groups"];
}

// Bands and segments narrower than a degree are printed with the decimals
// that show them (not "13..13 °C").
TEST(CliDiagnose, NarrowTemperatureBandsArePrintedWithTheirDecimals) {
  ScratchDir dir;
  write_narrow_record(dir / "narrow.csv");
  const auto r = run_cli(dir, "diagnose narrow.csv --model T");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ranges = printed_ranges(r.out);
  ASSERT_GE(ranges.size(), 4u) << r.out;
  for (const auto& [lo, hi] : ranges) EXPECT_NE(lo, hi) << r.out;
  EXPECT_NE(r.out.find("by temperature: 13.0.."), std::string::npos) << r.out;  // bands 0.15 °C wide
}

// With nothing significant, the several-channel summary says so rather than
// naming a "best candidate".
TEST(CliDiagnose, TheSummarySaysWhenNoCandidateHelps) {
  ScratchDir dir;
  write_narrow_record(dir / "narrow.csv");
  const auto r = run_cli(dir, "diagnose narrow.csv --model T --gyro-col gyro_dph,gyro2_dph");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string summary = r.out.substr(r.out.find("summary ("));
  EXPECT_EQ(summary.find("best candidate"), std::string::npos) << summary;
  EXPECT_NE(summary.find("missing effect"), std::string::npos) << summary;
  for (const char* channel : {"gyro_dph ", "gyro2_dph "}) {
    const std::size_t row = summary.find(std::string("\n  ") + channel);
    ASSERT_NE(row, std::string::npos) << summary;
    EXPECT_NE(summary.substr(row, summary.find('\n', row + 1) - row).find("none significant (top: "),
              std::string::npos)
        << summary;
  }
}

// A count of one takes the singular ("only 1 window", not "only 1 windows").
TEST(CliDiagnose, ARecordOfOneWindowSaysSoInTheSingular) {
  ScratchDir dir;
  std::string csv = "time_s,temp_c,gyro_dph\n";
  for (int k = 0; k < 120; ++k) csv += std::to_string(k) + "," + std::to_string(20.0 + 0.01 * k) + ",1.5\n";
  write_text(dir / "one.csv", csv);
  const auto r = run_cli(dir, "diagnose one.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("only 1 window:"), std::string::npos) << r.err;
}

TEST(CliDiagnose, AModelWithEveryTermHasNothingLeftToTry) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  std::string every;
  for (const effects::Effect* e : effects::registry()) every += (every.empty() ? "" : " + ") + std::string(e->name);
  const auto r = run_cli(dir, "diagnose c.csv --model '" + every + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nothing left to try"), std::string::npos) << r.err;
}

TEST(CliDiagnose, BadInputIsTheFittingCatalogue) {
  ScratchDir dir;
  write_text(dir / "d.csv", "time_s,temp_c,gyro_dph\n0,20,-7\n1,x,-7\n");
  auto r = run_cli(dir, "diagnose d.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("d.csv:3"), std::string::npos) << r.err;
  r = run_cli(dir, "diagnose missing.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos);
  r = run_cli(dir, "diagnose d.csv --model 'T + bogus'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown term 'bogus'"), std::string::npos);
}

}  // namespace
}  // namespace gyrotherm
