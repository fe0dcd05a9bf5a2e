// `gyrotherm plan` end to end: the contract's JSON, the files it writes (the
// scenario runs in `simulate` as is), the planned test against the standard
// recipes on the paper's model, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "sim/config_loader.h"

namespace gyrotherm {
namespace {

using testing::CliResult;
using testing::ScratchDir;
using testing::expect_refused;
using testing::run_cli;
using testing::slurp;

TEST(CliPlan, ThePapersModelPlanIsShorterThanEveryRecipeAndItsFilesRun) {
  ScratchDir dir;
  const CliResult r = run_cli(dir, "plan --json --out p --verify 24 --seed 5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"duration_s", "scenario_file", "setpoint_file", "predicted_se", "baselines",
                          "achieved_se", "coverage_95"})
    EXPECT_TRUE(j.contains(key)) << key;
  const double plan_s = j["duration_s"].get<double>();
  // The aim on the default rig: at least 30 % shorter than the best recipe.
  double best = INFINITY;
  for (const auto& b : j["baselines"]) {
    ASSERT_TRUE(b.contains("recipe") && b.contains("duration_s"));
    if (!b["duration_s"].is_null()) best = std::min(best, b["duration_s"].get<double>());
  }
  EXPECT_LE(plan_s, 0.7 * best) << r.out;
  EXPECT_TRUE(j["baselines"][0]["duration_s"].is_null()) << "a warm-up never separates T from dT";
  for (const auto& [term, se] : j["predicted_se"].items())
    EXPECT_LE(se.get<double>(), j["target_se"][term].get<double>() * (1 + 1e-12)) << term;
  for (const auto& [term, c] : j["coverage_95"].items()) EXPECT_GE(c.get<double>(), 0.75) << term;  // 24 seeds

  // The scenario runs as written, and is the planned profile.
  EXPECT_EQ(j["scenario_file"], "p/plan.toml");
  const sim::Scenario sc = sim::load_scenario(dir / "p/plan.toml");
  EXPECT_EQ(sc.segments.size(), j["profile"]["segments"].size());
  const CliResult s = run_cli(dir, "simulate p/plan.toml -o run.csv --json");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_NEAR(nlohmann::json::parse(s.out)["duration_s"].get<double>(), plan_s, 1.0);
  const std::string csv = slurp(dir / "p/plan_setpoint.csv");
  EXPECT_EQ(csv.rfind("time_s,setpoint_c\n", 0), 0u);
  EXPECT_TRUE(std::filesystem::exists(dir / "p/plan.png"));
  // The text report names the recipes and the files.
  const CliResult t = run_cli(dir, "plan --out q --model 'T + dT' --se dT=0.05 --longest 6");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  for (const char* s2 : {"planned test:", "soak staircase", "triangle, one cycle", "q/plan.toml"})
    EXPECT_NE(t.out.find(s2), std::string::npos) << s2 << "\n" << t.out;
}

// The warm-up from cold is never the plan (its cold soak is not counted);
// where it meets the target sooner, the plan says why it is not the plan
// rather than list a shorter recipe beside "the shortest test" unexplained.
TEST(CliPlan, AShorterWarmUpIsExplained) {
  ScratchDir dir;
  const CliResult r = run_cli(dir, "plan --json --out p --model 'T + T^2 + dT' --separate "
                                   "'T^3=9.75e-07,T^4=1.03e-08,T^5=1.43e-10' --range -60,130");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& warmup = j["baselines"][0];
  ASSERT_EQ(warmup["recipe"], "warm-up from cold");
  ASSERT_FALSE(warmup["duration_s"].is_null()) << r.out;
  ASSERT_LT(warmup["duration_s"].get<double>(), j["duration_s"].get<double>()) << r.out;
  bool said = false;
  for (const auto& n : j["notes"]) said = said || n.get<std::string>().find("the warm-up from cold meets") == 0;
  EXPECT_TRUE(said) << j["notes"];
}

struct BadPlan {
  std::string args, expected;
};

class CliPlanBadInput : public ::testing::TestWithParam<BadPlan> {};

TEST_P(CliPlanBadInput, ClearMessageExitTwoNoFiles) {
  ScratchDir dir;
  testing::write_text(dir / "marker", "a file, not a folder\n");
  const std::string& args = GetParam().args;
  expect_refused(dir, (args.find("--out") == std::string::npos ? "plan --out p " : "plan ") + args, GetParam().expected);
  EXPECT_FALSE(std::filesystem::exists(dir / "p")) << GetParam().args;
  EXPECT_EQ(dir.file_count(), 1u) << GetParam().args;  // the marker alone
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliPlanBadInput,
    ::testing::Values(
        BadPlan{"--max-rate 0", "--max-rate '0': must be > 0 °C/min"},
        BadPlan{"--range 60,-40", "the low end must be below the high end"},
        BadPlan{"--verify 1", "--verify 1: give the number of simulated tests"},
        BadPlan{"--se T=1e-9 --longest 3", "no test of at most 3.00 h at these limits"},
        BadPlan{"--tau 1200 --model 'T + dT + grad' --se grad=0.01 --longest 3",
                "cannot be identified at these limits by any test of at most 3.00 h"},
        BadPlan{"--model 'T + lag' --rel-se lag=0.2", "no prior value of lag"},
        BadPlan{"--separate missing.json", "--separate missing.json: cannot open the file"},
        BadPlan{"--min-soak 7200 --longest 2", "--min-soak 7200 s is not shorter than --longest 2 h"},
        BadPlan{"--out marker", "--out marker: is a file, not a folder"},
        BadPlan{"--out marker/sub", "--out marker/sub: marker is not a folder this user can write in"},
        BadPlan{"--longest 0.1", "--longest 0.1 h: a test needs at least 8 windows"},
        BadPlan{"--longest 800", "--longest '800': must be > 0 and <= 720 h"},
        BadPlan{"--tau 0", "--tau '0': must be > 0 s"},
        BadPlan{"--min-soak -5", "--min-soak '-5': must be >= 0 s"},
        BadPlan{"--model 'T + lag' --se T=1 --param lag=10", "--param lag=10: time_constant_s must lie in [60, 14400]"},
        BadPlan{"--prior grad=0.1", "--prior grad=0.1: grad is not in the model"},
        BadPlan{"--separate grad,lag", "--separate grad: no prior value of grad's coefficient"},
        BadPlan{"--se dT=abc", "--se dT: 'abc' is not a number"}));

}  // namespace
}  // namespace gyrotherm
