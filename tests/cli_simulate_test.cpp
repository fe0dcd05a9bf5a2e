// `gyrotherm simulate` end to end: files written, byte-identical for a seed,
// and every bad input a clear message, exit code 2 and no output file.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.h"
#include "sim/effects/effect.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

// A short cycle (so the test is quick) on the shipped rig and gyro.
std::string short_scenario() {
  return "name = \"short\"\nrig = \"" + source_path("scenarios/rig_shield.toml") +
         "\"\ngyro = \"" + source_path("scenarios/gyro.toml") +
         "\"\nseed = 7\nstart_c = 20.0\n"
         "[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_min = 20\n"
         "[[segment]]\nkind = \"ramp\"\ntarget_c = 40.0\nrate_c_per_min = 5.0\n"
         "[[segment]]\nkind = \"hold\"\ntemp_c = 40.0\nduration_min = 20\n";
}

TEST(CliSimulate, WritesCsvAndTruthAndIsDeterministic) {
  ScratchDir dir;
  write_text(dir / "s.toml", short_scenario());
  auto r = run_cli(dir, "simulate s.toml -o a.csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote a.csv"), std::string::npos) << r.out;
  ASSERT_EQ(run_cli(dir, "simulate s.toml -o b.csv").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "simulate s.toml --seed 8 -o c.csv").exit_code, 0);
  EXPECT_EQ(slurp(dir / "a.csv"), slurp(dir / "b.csv"));
  // The same truth, each naming its own record (the same bytes).
  nlohmann::json ta = nlohmann::json::parse(slurp(dir / "a.truth.json")), tb = nlohmann::json::parse(slurp(dir / "b.truth.json"));
  EXPECT_EQ(ta["record"]["file"], "a.csv");
  EXPECT_EQ(tb["record"]["file"], "b.csv");
  ta["record"].erase("file");
  tb["record"].erase("file");
  EXPECT_EQ(ta, tb);
  EXPECT_NE(slurp(dir / "a.csv"), slurp(dir / "c.csv"));

  const std::string csv = slurp(dir / "a.csv");
  EXPECT_NE(csv.find("\ntime_s,chamber_c,case_c,temp_c,temp2_c,gyro_dph,bias_true_dph\n"),
            std::string::npos);
  const auto truth = nlohmann::json::parse(slurp(dir / "a.truth.json"));
  EXPECT_EQ(truth["seed"], 7);
  EXPECT_EQ(truth["coefficients"]["dT"], 1.81);
  EXPECT_EQ(truth["coefficients"]["1"], -7.07712);
  EXPECT_EQ(truth["scenario"]["sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(truth["rig"]["sha256"].get<std::string>().size(), 64u);
  EXPECT_GT(truth["solver"]["steps"].get<long>(), 0);
  EXPECT_EQ(truth["rows"], 20 * 60 + 4 * 60 + 20 * 60 + 1);
}

TEST(CliSimulate, HiddenEffectAppearsInTheTruth) {
  ScratchDir dir;
  write_text(dir / "s.toml", short_scenario());
  auto r = run_cli(dir, "simulate s.toml --hidden grad=0.02 --hidden 'T^3=1e-7' -o h.csv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);  // stdout is one JSON object
  EXPECT_EQ(summary["csv"], "h.csv");
  const auto truth = nlohmann::json::parse(slurp(dir / "h.truth.json"));
  EXPECT_EQ(truth["coefficients"]["grad"], 0.02);
  EXPECT_EQ(truth["coefficients"]["T^3"], 1e-7);
  EXPECT_EQ(truth["hidden"]["grad"]["coefficient"], 0.02);
}

struct BadCase {
  std::string name;
  std::string scenario;  // written to s.toml ("" = do not write)
  std::string args;      // after "simulate"
  std::vector<std::string> fragments;
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class CliSimulateBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(CliSimulateBadInput, ClearMessageExitTwoNoOutput) {
  const BadCase& c = GetParam();
  ScratchDir dir;
  if (!c.scenario.empty()) write_text(dir / "s.toml", c.scenario);
  const std::size_t before = dir.file_count();
  const bool has_output = c.args.find("-o ") != std::string::npos;
  const auto r = run_cli(dir, "simulate " + c.args + (has_output ? "" : " -o out.csv"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  for (const std::string& fragment : c.fragments)
    EXPECT_NE(r.err.find(fragment), std::string::npos)
        << "stderr: " << r.err << "\nmissing: " << fragment;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(dir.file_count(), before) << "an output file was left behind";
}

std::string with_rig(const std::string& rest) {
  return "rig = \"rig.toml\"\ngyro = \"" + source_path("scenarios/gyro.toml") + "\"\n" + rest;
}

// Two lines naming the shipped rig and gyro, then the rest.
std::string shipped(const std::string& rest) {
  return "rig = \"" + source_path("scenarios/rig_shield.toml") + "\"\ngyro = \"" +
         source_path("scenarios/gyro.toml") + "\"\n" + rest;
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, CliSimulateBadInput,
    ::testing::Values(
        BadCase{"missing_file", "", "nope.toml", {"nope.toml", "no such file"}},
        BadCase{"unknown_key",
                shipped("name = \"x\"\nsample_rate = 1.0\n[[segment]]\nkind = \"free\"\nduration_h = 1\n"),
                "s.toml",
                {"s.toml:4", "unknown key 'sample_rate'", "sample_rate_hz"}},
        BadCase{"negative_duration",
                shipped("[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_min = -3\n"),
                "s.toml",
                {"s.toml:6", "duration_min = -3", "must be > 0"}},
        BadCase{"zero_ramp_rate",
                shipped("[[segment]]\nkind = \"ramp\"\ntarget_c = 20.0\nrate_c_per_min = 0\n"),
                "s.toml",
                {"s.toml:6", "rate_c_per_min = 0", "must be > 0"}},
        BadCase{"negative_ramp_rate",
                shipped("[[segment]]\nkind = \"ramp\"\ntarget_c = 20.0\nrate_c_per_min = -1\n"),
                "s.toml",
                {"s.toml:6", "rate_c_per_min = -1", "must be > 0"}},
        BadCase{"set_point_above_range",
                shipped("[[segment]]\nkind = \"hold\"\ntemp_c = 140.0\nduration_h = 1\n"),
                "s.toml",
                {"s.toml:3", "temp_c = 140", "outside the chamber's range, -60..130", "rig_shield.toml"}},
        BadCase{"start_below_range",
                shipped("start_c = -70.0\n[[segment]]\nkind = \"free\"\nduration_h = 1\n"),
                "s.toml",
                {"s.toml", "start_c = -70", "-60..130"}},
        BadCase{"rig_file_missing",
                with_rig("[[segment]]\nkind = \"free\"\nduration_h = 1\n"),
                "s.toml --rig bad_rig.toml",
                {"bad_rig.toml", "no such file"}},
        BadCase{"unknown_hidden_term",
                shipped("[[segment]]\nkind = \"free\"\nduration_h = 1\n"),
                "s.toml --hidden gradient=0.1",
                {"unknown term 'gradient'", effects::hidden_names()}},
        BadCase{"output_folder_missing",
                shipped("[[segment]]\nkind = \"free\"\nduration_h = 0.01\n"),
                "s.toml -o no/such/dir/x.csv",
                {"no/such/dir/x.csv", "cannot create the output file"}}),
    [](const auto& param_info) { return param_info.param.name; });

TEST(CliSimulate, MissingOutputOption) {
  ScratchDir dir;
  const auto r = run_cli(dir, "simulate s.toml");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--output is required"), std::string::npos) << r.err;
}

TEST(CliSimulate, NegativeCapacityInRigNamesFileAndKey) {
  ScratchDir dir;
  write_text(dir / "s.toml", with_rig("[[segment]]\nkind = \"free\"\nduration_h = 1\n"));
  write_text(dir / "rig.toml", "[block]\nanode_capacity_j_per_k = -500.0\n");
  const auto r = run_cli(dir, "simulate s.toml -o out.csv");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("rig.toml:2: block.anode_capacity_j_per_k = -500: must be > 0"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
}

TEST(CliSimulate, FailedRunKeepsThePreviousResult) {
  ScratchDir dir;
  write_text(dir / "s.toml", short_scenario());
  ASSERT_EQ(run_cli(dir, "simulate s.toml -o run.csv").exit_code, 0);
  const std::string before = slurp(dir / "run.csv");
  // Same output, but the run fails on a bad hidden term: nothing is touched.
  EXPECT_EQ(run_cli(dir, "simulate s.toml --hidden bogus=1 -o run.csv").exit_code, 2);
  EXPECT_EQ(slurp(dir / "run.csv"), before);
}

}  // namespace
}  // namespace gyrotherm
