// `gyrotherm score`: the --json contract, the same scoreboard on 1 and 2
// threads and on 2 MPI ranks, files only with --out, the shipped baseline
// passes and a starved or edited one fails naming engine and metric, and bad
// input exits 2. Campaigns are short (a 2.3 h profile, or 20 trials of the
// cycle for the shipped baseline).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;
using Json = nlohmann::json;

// The command that made results/score_baseline.json (docs_score.md).
const std::string kBaselineCampaign = "score '" + source_path("scenarios/cycle.toml") + "' --trials 20 --seed 1";

void write_short_scenario(const ScratchDir& dir, const std::string& extra = "") {
  write_text(dir / "short.toml", short_scenario_text(3, source_path("scenarios/gyro.toml"), extra));
}

// The scoreboard without what measures time or how it ran.
Json without_timing(Json j) {
  j.erase("run");
  for (auto& [name, e] : j["engines"].items()) {
    std::vector<std::string> timing;
    for (const auto& [key, value] : e.items())
      if (key.rfind("seconds", 0) == 0) timing.push_back(key);
    for (const std::string& key : timing) e.erase(key);
  }
  return j;
}

TEST(CliScore, JsonHasTheContractFields) {
  ScratchDir dir;
  write_short_scenario(dir);
  const auto r = run_cli(dir, "score short.toml --trials 4 --engines ols,iafsa,cmaes --threads 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);  // stdout holds the JSON alone
  EXPECT_EQ(j["scenario"], "short");
  EXPECT_EQ(j["trials"], 4);
  EXPECT_EQ(j["seed"], 3);  // the scenario's
  EXPECT_EQ(j["model"], "T + T^2 + dT");
  ASSERT_EQ(j["engines"].size(), 3u);
  for (const char* e : {"ols", "iafsa", "cmaes"}) {
    const Json& s = j["engines"][e];
    for (const char* key : {"success_rate", "evals_to_target_median", "seconds_median", "gap_median",
                            "coefficient_error_median", "ratio_median", "ci95", "terminations"})
      EXPECT_TRUE(s.contains(key)) << e << " " << key;
    for (const char* term : {"1", "T", "T^2", "dT"}) EXPECT_TRUE(s["coefficient_error_median"].contains(term));
    EXPECT_EQ(s["success_rate"], 1.0) << e;
    EXPECT_GT(s["ratio_median"].get<double>(), 1.0) << e;
  }
  EXPECT_EQ(j["engines"]["ols"]["evals_to_target_median"], 1.0);
  EXPECT_LE(j["engines"]["iafsa"]["gap_median"].get<double>(), 1e-6);
  EXPECT_EQ(j["run"]["processes"], 1);
  // Plain progress lines when stderr is not a terminal.
  EXPECT_NE(r.err.find("score: 4/4 trials"), std::string::npos) << r.err;
}

TEST(CliScore, OneAndTwoThreadsGiveTheSameScoreboard) {
  ScratchDir dir;
  write_short_scenario(dir, "[spread]\nb1_dph_per_c = 0.2\narw_deg_per_sqrt_h = 0.3\n");
  const auto one = run_cli(dir, "score short.toml --trials 6 --seed 11 --threads 1 --json --out one");
  const auto two = run_cli(dir, "score short.toml --trials 6 --seed 11 --threads 2 --json --out two");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const Json a = Json::parse(one.out), b = Json::parse(two.out);
  EXPECT_EQ(a["run"]["threads"], 1);
  EXPECT_EQ(b["run"]["threads"], 2);
  EXPECT_EQ(a["engines"].size(), 8u);  // every registered engine
  EXPECT_EQ(a["spread"]["b1_dph_per_c"], 0.2);
  EXPECT_EQ(without_timing(a), without_timing(b));
  EXPECT_EQ(slurp(dir / "one/convergence.csv"), slurp(dir / "two/convergence.csv"));
}

TEST(CliScore, FilesOnlyWithOut) {
  ScratchDir dir;
  write_short_scenario(dir);
  const auto quiet = run_cli(dir, "score short.toml --trials 2 --engines ols,cmaes");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(dir.file_count(), 1u) << "only the scenario: no files without --out";
  EXPECT_NE(quiet.out.find("cmaes"), std::string::npos) << quiet.out;

  const auto r = run_cli(dir, "score short.toml --trials 3 --engines ols,iafsa,cmaes --out board");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"scoreboard.json", "scoreboard.md", "convergence.csv", "convergence.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "board" / f)) << f;
  EXPECT_EQ(slurp(dir / "board/convergence.png").substr(1, 3), "PNG");
  const std::string csv = slurp(dir / "board/convergence.csv");
  EXPECT_EQ(csv.rfind("engine,evaluations,gap_q25,gap_median,gap_q75\nols,1,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\niafsa,1,"), std::string::npos);
  const std::string md = slurp(dir / "board/scoreboard.md");
  EXPECT_NE(md.find("| iafsa | 100 % (3/3) |"), std::string::npos) << md;
  EXPECT_EQ(Json::parse(slurp(dir / "board/scoreboard.json"))["trials"], 3);
}

TEST(CliScore, ShippedBaselinePasses) {
  ScratchDir dir;
  const auto r = run_cli(dir, kBaselineCampaign + " --threads 2 --baseline '" +
                                  source_path("results/score_baseline.json") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("no engine is worse beyond Monte Carlo noise"), std::string::npos) << r.out;
}

TEST(CliScore, StarvedEngineFailsTheShippedBaseline) {
  ScratchDir dir;
  const auto r = run_cli(dir, kBaselineCampaign + " --threads 2 --budget iafsa=300 --json --baseline '" +
                                  source_path("results/score_baseline.json") + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("iafsa: success_rate = 0 "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("worse than the baseline"), std::string::npos) << r.err;
  for (const char* other : {"ols:", "cmaes:", "pso:"}) EXPECT_EQ(r.err.find(other), std::string::npos) << r.err;
  EXPECT_NO_THROW(Json::parse(r.out));  // the scoreboard is still printed
}

TEST(CliScore, EditedBaselineFailsNamingEngineAndMetric) {
  ScratchDir dir;
  write_short_scenario(dir);
  const std::string campaign = "score short.toml --trials 5 --engines ols,cmaes";
  const auto made = run_cli(dir, campaign + " --json");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  Json j = Json::parse(made.out);
  write_text(dir / "same.json", j.dump());
  j["engines"]["cmaes"]["ratio_median"] = 1e6;
  j["engines"]["cmaes"]["ci95"]["ratio_median"] = {1e6, 1e6};
  write_text(dir / "edited.json", j.dump());

  EXPECT_EQ(run_cli(dir, campaign + " --baseline same.json").exit_code, 0);
  const auto r = run_cli(dir, campaign + " --baseline edited.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cmaes: ratio_median = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("below the baseline's 1e+06"), std::string::npos) << r.err;
}

TEST(CliScore, TwoMpiRanksGiveTheSingleProcessScoreboard) {
#ifndef GYROTHERM_MPIEXEC
  GTEST_SKIP() << "built without MPI (GYROTHERM_WITH_MPI=OFF)";
#else
  ScratchDir dir;
  write_short_scenario(dir);
  const std::string args = " score short.toml --trials 5 --engines ols,stepwise,iafsa,pso,cmaes --json";
  const auto single = run_cli(dir, args + " --threads 1");
  ASSERT_EQ(single.exit_code, 0) << single.err;
  const auto mpi = run_shell(dir, std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '") +
                                      GYROTHERM_MPIEXEC + "' -np 2 --oversubscribe '" + GYROTHERM_CLI + "'" + args);
  ASSERT_EQ(mpi.exit_code, 0) << mpi.err;
  const Json a = Json::parse(single.out), b = Json::parse(mpi.out);  // one JSON: only rank 0 prints
  EXPECT_EQ(b["run"]["processes"], 2);
  EXPECT_EQ(without_timing(a), without_timing(b));
  EXPECT_NE(mpi.err.find("rank 0 of 2"), std::string::npos) << mpi.err;
#endif
}

TEST(CliScore, BadInputExitsTwo) {
  ScratchDir dir;
  write_short_scenario(dir);
  const std::pair<std::string, std::string> cases[] = {
      {"score short.toml --trials 0", "--trials 0: must be a whole number from 1"},
      {"score short.toml --engines ols,ga", "unknown engine 'ga'"},
      {"score short.toml --budget lots", "--budget lots: 'lots' is not a whole number"},
      {"score short.toml --engines ols --budget iafsa=10", "'iafsa' is not among the campaign's engines"},
      {"score short.toml --option fish=3", "--option fish=3: expected ENGINE:KEY=VALUE"},
      {"score short.toml --engines iafsa --option iafsa:fish=0", "iafsa option fish=0"},
      {"score short.toml --baseline none.json", "none.json: no such file"},
      {"score nope.toml", "nope.toml: no such file"},
      {"score short.toml --threads 2000", "--threads '2000': must be 0 (one per core) or a whole number from 1 to 1024"},
      {"score short.toml --trials 2 --budget 5 6", "The following argument was not expected: 6"},
  };
  for (const auto& [args, message] : cases) {
    const auto r = run_cli(dir, args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
  }
  write_text(dir / "bad.json", "{\"model\": \"T + T^2 + dT\", \"target_relative\": 1e-6, \"trials\": 3}");
  const auto r = run_cli(dir, "score short.toml --trials 2 --engines ols --baseline bad.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.json: engines: expected an object"), std::string::npos) << r.err;
  write_short_scenario(dir, "[spread]\nb1 = 0.1\n");
  const auto s = run_cli(dir, "score short.toml --trials 2");
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("short.toml:27: unknown key 'spread.b1'"), std::string::npos) << s.err;
}

}  // namespace
}  // namespace gyrotherm
