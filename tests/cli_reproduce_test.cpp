// A reduced `gyrotherm reproduce` (shorter profiles, three engines): the
// report's structure, and that compensation improves every test. The full
// figures live in results/ and come from the README's main command.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

std::string files(const std::string& rig) {
  return "rig = \"" + source_path("scenarios/" + rig) + "\"\ngyro = \"" +
         source_path("scenarios/gyro.toml") + "\"\n";
}

void write_short_scenarios(const ScratchDir& dir) {
  std::filesystem::create_directories(dir / "sc");
  write_text(dir / "sc/cycle.toml",
             "name = \"cycle\"\nseed = 11\nstart_c = 20.0\n" + files("rig_shield.toml") +
                 "[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_min = 40\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = 60.0\nrate_c_per_min = 5.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = 60.0\nduration_min = 60\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = -40.0\nrate_c_per_min = 5.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = -40.0\nduration_min = 60\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = 60.0\nrate_c_per_min = 5.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = 60.0\nduration_min = 60\n");
  write_text(dir / "sc/random.toml",
             "name = \"random\"\nseed = 12\nstart_c = 15.0\ninitial = \"steady\"\n" + files("rig_ins.toml") +
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = -20.0\nrate_c_per_min = 1.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = -20.0\nduration_h = 2\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = 30.0\nrate_c_per_min = 1.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = 30.0\nduration_h = 2\n"
                 "[[segment]]\nkind = \"free\"\nduration_h = 1\n");
  write_text(dir / "sc/warmup.toml",
             "name = \"warmup\"\nseed = 13\nchamber = false\nroom_c = 23.0\n" + files("rig_room.toml") +
                 "[[segment]]\nkind = \"free\"\nduration_h = 6\n");
}

TEST(CliReproduce, ReducedRunWritesTheReportAndCompensationHelps) {
  ScratchDir dir;
  write_short_scenarios(dir);
  const auto r = run_cli(dir, "reproduce --scenarios sc --engines ols,stepwise,iafsa --out out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("[100%]"), std::string::npos) << "progress is shown";
  // Done only once everything, figures included, is written: the last line, after the figures.
  const std::size_t done = r.err.rfind("[100%] done\n");
  ASSERT_NE(done, std::string::npos) << r.err;
  EXPECT_EQ(done + std::string("[100%] done\n").size(), r.err.size()) << r.err;
  EXPECT_LT(r.err.find("drawing the figures"), done) << r.err;
  EXPECT_EQ(r.err.find("[100%]"), done) << "nothing else at 100 %:\n" << r.err;
  EXPECT_NE(r.out.find("Table 1, side by side"), std::string::npos) << r.out;

  const auto j = nlohmann::json::parse(slurp(dir / "out/table1.json"));
  ASSERT_TRUE(j["cycle"].contains("raw_dph"));
  for (const char* e : {"ols", "stepwise", "iafsa"}) {
    const auto& c = j["cycle"]["engines"][e];
    for (const char* key : {"after_dph", "ratio", "coefficients", "coefficient_error", "evaluations"})
      EXPECT_TRUE(c.contains(key)) << e << " " << key;
    EXPECT_FALSE(c.contains("seconds")) << "run times go to the terminal, not into the file";
    EXPECT_LT(c["after_dph"].get<double>(), j["cycle"]["raw_dph"].get<double>()) << e;
    for (const char* test : {"test1", "test2"}) {
      const auto& t = j[test]["engines"][e];
      EXPECT_LT(t["after_dph"].get<double>(), j[test]["before_dph"].get<double>()) << test << " " << e;
      EXPECT_GT(t["times"].get<double>(), 1.0) << test << " " << e;
    }
  }
  // Nothing beats least squares on the training data.
  EXPECT_GE(j["cycle"]["engines"]["iafsa"]["after_dph"].get<double>(),
            j["cycle"]["engines"]["ols"]["after_dph"].get<double>() * (1 - 1e-12));
  EXPECT_EQ(j["paper"]["cycle"]["iafsa_dph"], 0.00185);
  EXPECT_EQ(j["paper"]["test1"]["times"], 7.91);
  EXPECT_EQ(j["seeds"]["cycle"], 11);
  EXPECT_EQ(j["seeds"]["test2"], 13);
  EXPECT_FALSE(j.contains("total_seconds"));

  const std::string md = slurp(dir / "out/table1.md");
  for (const char* text : {"| raw | 0.00953 |", "| IAFSA | 0.00185 (5.15×) |", "## Test 1", "## Test 2",
                           "What the engines can and cannot do", "a term is dropped"})
    EXPECT_NE(md.find(text), std::string::npos) << text;
  // The tests are described by the scenarios that ran (Test 1: 35 + 120 + 50 + 120 + 60 min), not by the shipped ones.
  for (const char* text : {"## Cycle (the training data: in the chamber, set points -40..60 °C, 4.5 h)",
                           "## Test 1 (the INS, random profile: in the chamber, set points -20..30 °C, 6.4 h)",
                           "## Test 2 (the INS, natural warm-up: in a 23 °C room, 6 h)"})
    EXPECT_NE(md.find(text), std::string::npos) << text << " not in:\n" << md;
  for (const char* png : {"fig2_cycle_1s.png", "fig3_cycle_100s.png", "fig4_5_cycle_compensated.png",
                          "fig6_7_test1.png", "fig8_9_test2.png"})
    EXPECT_GT(std::filesystem::file_size(dir / "out" / png), 10000u) << png;
}

// The main job leaves its files as they were: a second run writes the same
// bytes (the repository stays clean), and the run times go to the terminal.
TEST(CliReproduce, ASecondRunWritesTheSameBytesAndTheTimesGoToTheTerminal) {
  ScratchDir dir;
  write_short_scenarios(dir);
  const std::string command = "reproduce --scenarios sc --engines ols,iafsa --out ";
  ASSERT_EQ(run_cli(dir, command + "a").exit_code, 0);
  const auto second = run_cli(dir, command + "b --json");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  for (const char* file : {"table1.json", "table1.md", "fig2_cycle_1s.png", "fig3_cycle_100s.png",
                           "fig4_5_cycle_compensated.png", "fig6_7_test1.png", "fig8_9_test2.png"})
    EXPECT_EQ(slurp(dir / "a" / file), slurp(dir / "b" / file)) << file;
  const auto printed = nlohmann::json::parse(second.out);
  EXPECT_GT(printed["total_seconds"].get<double>(), 0.0);
  EXPECT_TRUE(printed["cycle"]["engines"]["iafsa"].contains("seconds"));
  EXPECT_EQ(printed["cycle"]["raw_dph"], nlohmann::json::parse(slurp(dir / "b/table1.json"))["cycle"]["raw_dph"]);
}

TEST(CliReproduce, UnknownEngineIsBadInput) {
  ScratchDir dir;
  write_short_scenarios(dir);
  const auto r = run_cli(dir, "reproduce --scenarios sc --engines ols,ga --out out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown engine 'ga'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/table1.json"));
}

TEST(CliReproduce, MissingScenarioFolder) {
  ScratchDir dir;
  const auto r = run_cli(dir, "reproduce --scenarios nowhere --out out");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nowhere/cycle.toml: no such file"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace gyrotherm
