// Diagnosis beyond the registry (issue 13): bias steps (mode hops), the
// user's own columns, effects a record cannot tell apart, and what is left.
// Every record is simulated, with the step or the column's effect added to
// the gyro output by the test, so the truth is known.

#include <gtest/gtest.h>

#include <set>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;
using Json = nlohmann::json;

// Rewrites a simulated CSV: gyro_dph (column 6) += extra(t), and with a
// column name, that column appended with column(t).
void rewrite(const ScratchDir& dir, const std::string& in, const std::string& out,
             const std::function<double(double)>& extra, const std::string& column = "",
             const std::function<double(double)>& value = {}) {
  std::ifstream src(dir / in);
  std::ofstream dst(dir / out);
  for (std::string line; std::getline(src, line);) {
    if (line.empty() || line[0] == '#') {
      dst << line << "\n";
      continue;
    }
    if (line.rfind("time_s", 0) == 0) {
      dst << line << (column.empty() ? "" : "," + column) << "\n";
      continue;
    }
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) f.push_back(cell);
    const double t = std::stod(f[0]);
    f[5] = fmt::format("{:.6f}", std::stod(f[5]) + extra(t));
    std::string joined;
    for (std::size_t i = 0; i < f.size(); ++i) joined += (i ? "," : "") + f[i];
    if (!column.empty()) joined += fmt::format(",{:.5f}", value(t));
    dst << joined << "\n";
  }
}

Json diagnose_json(const ScratchDir& dir, const std::string& args) {
  const auto r = run_cli(dir, "diagnose " + args + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? Json::parse(r.out) : Json{};
}

// `fit DATA --model MODEL --json` (ols): a term's coefficient, parameters
// and 95 % interval when added alone to the model.
Json fit_json(const ScratchDir& dir, const std::string& csv, const std::string& model) {
  const auto r = run_cli(dir, "fit " + csv + " --model '" + model + "' --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? Json::parse(r.out) : Json{};
}

// The true coefficient lies in a fit's 95 % interval for the term.
void expect_within_interval(const Json& fit, const std::string& term, double truth) {
  const auto iv = fit["intervals_95"][term].get<std::vector<double>>();
  ASSERT_EQ(iv.size(), 2u) << fit["intervals_95"];
  EXPECT_TRUE(iv[0] <= truth && truth <= iv[1])
      << term << " " << fit["coefficients"][term] << ", 95 % [" << iv[0] << ", " << iv[1] << "], truth " << truth;
}

// What a plan command asks for: its model, --separate's sizes and --param's
// values by term, and --range, as printed.
struct PlanArgs {
  std::string model, range;
  std::map<std::string, double> sizes, params;
};
// diagnose --json's `plan`: what its plan_command says, as data.
PlanArgs plan_args(const Json& plan) {
  PlanArgs a;
  a.model = plan["model"].get<std::string>();
  a.range = fmt::format("{:g},{:g}", plan["range_c"][0].get<double>(), plan["range_c"][1].get<double>());
  for (const auto& [name, size] : plan["separate"].items()) a.sizes[name] = size.get<double>();
  for (const auto& [name, value] : plan["param"].items()) a.params[name] = value.get<double>();
  return a;
}

struct StepCase {
  std::string scenario;
  double time_s;
  double size_dph;
};
void PrintTo(const StepCase& c, std::ostream* os) { *os << c.scenario << " " << c.time_s << " " << c.size_dph; }

class Steps : public ::testing::TestWithParam<StepCase> {};

// A single step at several times and signs: located within an hour, its size
// within its interval, named in the verdict, no smooth term significant, and
// the model with the step near the floor.
TEST_P(Steps, AreFoundSizedAndNamedNotPassedOffAsDrift) {
  const StepCase& c = GetParam();
  ScratchDir dir;
  simulate_shipped(dir, c.scenario, "", "clean.csv");
  rewrite(dir, "clean.csv", "step.csv", [&](double t) { return t >= c.time_s ? c.size_dph : 0.0; });
  const Json j = diagnose_json(dir, "step.csv");
  ASSERT_FALSE(j["events"].empty()) << j["verdict"];
  const Json& e = j["events"][0];
  EXPECT_EQ(e["kind"], "step");
  EXPECT_NEAR(e["time_s"].get<double>(), c.time_s, 3600.0);
  EXPECT_LE(e["size_interval_dph"][0].get<double>(), c.size_dph);
  EXPECT_GE(e["size_interval_dph"][1].get<double>(), c.size_dph);
  EXPECT_TRUE(e["significant"].get<bool>());
  EXPECT_NE(j["verdict"].get<std::string>().find("step@"), std::string::npos) << j["verdict"];
  for (const Json& m : j["missing_effects"])
    if (m["significant"].get<bool>()) {
      EXPECT_EQ(m["term"].get<std::string>().rfind("step@", 0), 0u) << m;
    }
  // The next command's model brings the instability near the floor.
  const std::string model = j["next_command"].get<std::string>().substr(j["next_command"].get<std::string>().find("--model"));
  const Json after = diagnose_json(dir, "step.csv " + model);
  EXPECT_LT(after["instability_dph"].get<double>(), 1.25 * after["noise_floor_dph"].get<double>());
  // fit takes the step term, and compensate applies it.
  const auto fit = run_cli(dir, "fit step.csv " + model + " -o fit.json");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_EQ(run_cli(dir, "compensate step.csv --fit fit.json -o comp.csv").exit_code, 0);
}

INSTANTIATE_TEST_SUITE_P(CycleAndRandom, Steps,
                         ::testing::Values(StepCase{"cycle", 7200, 0.006}, StepCase{"cycle", 19800, 0.006},
                                           StepCase{"cycle", 25200, -0.006}, StepCase{"random", 19800, -0.006},
                                           StepCase{"random", 90000, 0.006}),
                         [](const auto& param_info) {
                           return fmt::format("{}_{:.0f}_{}", param_info.param.scenario, param_info.param.time_s,
                                              param_info.param.size_dph > 0 ? "up" : "down");
                         });

// A mode hop under slow noise: the cycle with the gyro's flicker replaced by
// white noise plus one Gauss–Markov process (correlation time 1 h, Allan peak
// 3.7e-4 °/h, σ ≈ 0.0006 °/h) and a +0.007 °/h step at 5.5 h: four times the
// floor diagnose reports on these records (0.00175 °/h). The step test's null is drawn from the record's identified noise, so
// the slow wander neither hides the step nor reads it as drift: it is located
// within an hour in at least 9 of 10 records.
TEST(DiagnoseBeyond, AStepUnderGaussMarkovNoiseIsLocatedInEightOfTen) {
  ScratchDir dir;
  std::filesystem::copy_file(source_path("scenarios/rig_shield.toml"), dir / "rig_shield.toml");
  {
    std::ifstream in(source_path("scenarios/gyro.toml"));
    std::ofstream out(dir / "gyro_gm.toml");
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("bias_instability_dph", 0) == 0) line = "bias_instability_dph = 3.7e-4";
      if (line.rfind("flicker_tau_min_s", 0) == 0) line = "flicker_tau_min_s = 3600.0";
      if (line.rfind("flicker_tau_max_s", 0) == 0) line = "flicker_tau_max_s = 3600.0";
      if (line.rfind("flicker_processes", 0) == 0) line = "flicker_processes = 1";
      out << line << "\n";
    }
    std::ifstream sc(source_path("scenarios/cycle.toml"));
    std::ofstream sc_out(dir / "cycle_gm.toml");
    for (std::string line; std::getline(sc, line);)
      sc_out << (line.rfind("gyro = ", 0) == 0 ? std::string("gyro = \"gyro_gm.toml\"") : line) << "\n";
  }
  int located = 0;
  std::string misses;
  for (int seed = 1; seed <= 10; ++seed) {
    ASSERT_EQ(run_cli(dir, "simulate cycle_gm.toml --seed " + std::to_string(seed) + " -o clean.csv").exit_code, 0);
    rewrite(dir, "clean.csv", "step.csv", [](double t) { return t >= 19800.0 ? 0.007 : 0.0; });
    const Json j = diagnose_json(dir, "step.csv");
    bool found = false;
    for (const Json& e : j["events"]) found = found || std::abs(e["time_s"].get<double>() - 19800.0) <= 3600.0;
    located += found;
    if (!found) misses += fmt::format("seed {}: {}\n", seed, j["verdict"].get<std::string>());
  }
  // About 4.5 times the floor: results/diagnosis_power.md locates 4 x steps
  // under Gauss-Markov noise in about 9 of 10 records over 100 seeds; on
  // these 10 seeds 8 (at least 9 while the test also took the noise
  // identified without any candidate as a test of its own, which passed on
  // 10-13 % of clean 75 h records).
  EXPECT_GE(located, 8) << misses;
}

TEST(DiagnoseBeyond, CleanRecordsReportNoStepInNineOfTen) {
  ScratchDir dir;
  int with_step = 0, anything = 0;
  for (int seed = 1; seed <= 10; ++seed) {
    simulate_shipped(dir, "cycle", "--seed " + std::to_string(seed), "clean.csv");
    const Json j = diagnose_json(dir, "clean.csv");
    for (const Json& e : j["events"]) with_step += e["significant"].get<bool>() ? 1 : 0;
    for (const Json& m : j["missing_effects"])
      anything += m["significant"].get<bool>() || m["group_significant"].get<bool>() ? 1 : 0;
  }
  EXPECT_LE(with_step, 1);
  EXPECT_LE(anything, 1);
}

// A bias that follows a logged supply voltage wandering apart from the
// temperature: the column is ranked first and significant, and adding it
// reaches the floor. The gyro columns themselves and the simulator's truth are
// never candidates.
TEST(DiagnoseBeyond, ALoggedColumnThatDrivesTheBiasIsFound) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "clean.csv");
  const auto volt = [](double t) {
    return 28.0 + 0.5 * std::sin(2.0 * M_PI * t / 7000.0) + 0.3 * std::sin(2.0 * M_PI * t / 2900.0 + 1.0);
  };
  rewrite(dir, "clean.csv", "volt.csv", [&](double t) { return 0.005 * (volt(t) - 28.0); }, "supply_v", volt);
  const Json j = diagnose_json(dir, "volt.csv");
  EXPECT_EQ(j["missing_effects"][0]["term"], "supply_v") << j["verdict"];
  EXPECT_TRUE(j["missing_effects"][0]["significant"].get<bool>());
  for (const Json& m : j["missing_effects"]) {
    EXPECT_NE(m["term"], "bias_true_dph");
    EXPECT_NE(m["term"], "gyro_dph");
    EXPECT_NE(m["term"], "time_s");
  }
  const Json added = diagnose_json(dir, "volt.csv --model 'T + T^2 + dT + supply_v'");
  EXPECT_LT(added["instability_dph"].get<double>(), 1.25 * added["noise_floor_dph"].get<double>());
  // --candidates restricts the set, or trims it.
  const Json only = diagnose_json(dir, "volt.csv --candidates T^3,grad");
  EXPECT_EQ(only["missing_effects"].size(), 2u);
  const Json without = diagnose_json(dir, "volt.csv --candidates -supply_v");
  for (const Json& m : without["missing_effects"]) EXPECT_NE(m["term"], "supply_v");
  const auto bad = run_cli(dir, "diagnose volt.csv --candidates nope_v");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("no numeric column 'nope_v'"), std::string::npos) << bad.err;
}

// A drift on a short monotone warm-up: time and the temperature terms are one
// group, and none of them is the answer; on the cycle (heating and cooling
// legs) the same drift is identified.
// A candidate's coefficient is its GLS estimate under the round's noise: as
// efficient as least squares or more, so the fit's least-squares estimate of
// the same model lies within the candidate's 95 % interval.
void expect_gls_near_fit(const Json& candidate, double least_squares) {
  const auto iv = candidate["coefficient_interval_95"].get<std::vector<double>>();
  EXPECT_TRUE(iv[0] <= least_squares && least_squares <= iv[1])
      << candidate["coefficient"] << " [" << iv[0] << ", " << iv[1] << "] vs least squares " << least_squares;
}

TEST(DiagnoseBeyond, DriftOnAMonotoneWarmUpCannotBeToldFromTemperature) {
  ScratchDir dir;
  write_text(dir / "warm2.toml",
             "name = \"warm2\"\nrig = \"" + source_path("scenarios/rig_room.toml") + "\"\ngyro = \"" +
                 source_path("scenarios/gyro.toml") +
                 "\"\nseed = 5\nsample_rate_hz = 1.0\nroom_c = 23.0\nchamber = false\ninitial = \"soaked\"\n"
                 "[[segment]]\nkind = \"free\"\nduration_h = 2\n");
  ASSERT_EQ(run_cli(dir, "simulate warm2.toml --hidden t=0.01 -o warm.csv").exit_code, 0);
  const Json j = diagnose_json(dir, "warm.csv");
  EXPECT_TRUE(testing::in_one_group(j["confounded"], "t", "T")) << j["confounding"];
  for (const Json& m : j["missing_effects"])
    if (!m["confounded_with"].empty()) {
      // A member of a group is never significant alone; the group may be.
      EXPECT_FALSE(m["significant"].get<bool>()) << m;
    }
  EXPECT_TRUE(j["next_command"].get<std::string>().find("+ t") == std::string::npos) << j["next_command"];
  EXPECT_EQ(j["plan_command"], "") << "the group did not pass the test: " << j["verdict"];

  // A stronger drift over 4 h: the group passes the test. Its first member
  // says so (group_significant), is not significant alone, the verdict names
  // the group, and nothing is said to remain once the group is in.
  write_text(dir / "warm4.toml", slurp(dir / "warm2.toml").replace(slurp(dir / "warm2.toml").find("duration_h = 2"), 14, "duration_h = 4"));
  ASSERT_EQ(run_cli(dir, "simulate warm4.toml --hidden t=0.05 -o warm4.csv").exit_code, 0);
  const Json w = diagnose_json(dir, "warm4.csv");
  const Json& first = w["missing_effects"][0];
  EXPECT_TRUE(first["group_significant"].get<bool>()) << w["verdict"];
  EXPECT_FALSE(first["significant"].get<bool>()) << first;
  EXPECT_FALSE(first["confounded_with"].empty()) << first;
  // The verdict names the group and says the record cannot tell which; why
  // is said once, in the group's own line (confounding), not again.
  EXPECT_NE(w["verdict"].get<std::string>().find("this record cannot tell which"), std::string::npos) << w["verdict"];
  EXPECT_EQ(w["verdict"].get<std::string>().find("cannot be told apart"), std::string::npos) << w["verdict"];
  EXPECT_EQ(w["verdict_data"]["kind"], "group") << w["verdict_data"];
  EXPECT_EQ(w["remaining"], "") << w["verdict"];
  EXPECT_EQ(w["verdict"].get<std::string>().find("structure remains"), std::string::npos) << w["verdict"];
  // A term that could not be fitted in several rounds is named once.
  std::set<std::string> named;
  for (const Json& s : w["skipped"]) {
    const std::string text = s.get<std::string>();
    EXPECT_TRUE(named.insert(text.substr(0, text.find(' '))).second) << w["skipped"];
  }

  // The test that would separate the group: its members but the intercept
  // and the model's terms, each sized (3 digits) by the model fitted with it
  // alone, its parameter (6 digits) likewise, over the record's temperatures
  // rounded outward to 5 °C; the report's next step. t's own coefficient is
  // that fit's, whose 95 % interval holds the hidden drift.
  ASSERT_TRUE(w.contains("plan")) << w["plan_command"];
  EXPECT_EQ(w["plan_command"].get<std::string>().rfind("gyrotherm plan --model 'T + T^2 + dT' --separate ", 0), 0u)
      << w["plan_command"];
  const PlanArgs plan = plan_args(w["plan"]);
  EXPECT_EQ(plan.model, "T + T^2 + dT") << w["plan_command"];
  std::map<std::string, double> expected;
  std::vector<double> range;  // the record's window-mean temperatures, °C
  std::vector<std::string> members = {first["term"].get<std::string>()};
  for (const Json& o : first["confounded_with"]) members.push_back(o.get<std::string>());
  for (const std::string& m : members) {
    if (m == "1" || m == "T" || m == "T^2" || m == "dT") continue;
    const Json f = fit_json(dir, "warm4.csv", "T + T^2 + dT + " + m);
    const double c = f["coefficients"][m].get<double>();
    ASSERT_EQ(plan.sizes.count(m), 1u) << m << ": " << w["plan_command"];
    EXPECT_NEAR(plan.sizes.at(m), c, 5e-3 * std::abs(c)) << m;
    if (f["parameters"].contains(m)) {
      ASSERT_EQ(plan.params.count(m), 1u) << m << ": " << w["plan_command"];
      for (const auto& [name, value] : f["parameters"][m].items())
        EXPECT_NEAR(plan.params.at(m), value.get<double>(), 5e-6 * value.get<double>()) << name;
    }
    expected[m] = c;
    if (m == "t") {
      expect_gls_near_fit(first, c);
      expect_within_interval(f, "t", 0.05);
    }
    range = f["data"]["temp_range_c"].get<std::vector<double>>();
  }
  EXPECT_GE(expected.size(), 2u) << w["confounded"];
  ASSERT_EQ(range.size(), 2u);
  EXPECT_EQ(plan.range, fmt::format("{:g},{:g}", 5.0 * std::floor(range[0] / 5.0), 5.0 * std::ceil(range[1] / 5.0)));
  EXPECT_EQ(plan.sizes.size(), expected.size()) << w["plan_command"];
  const auto text = run_cli(dir, "diagnose warm4.csv");
  EXPECT_NE(text.out.find("next: to design a test that separates them: " + w["plan_command"].get<std::string>() + "\n"),
            std::string::npos)
      << text.out;

  // Identified on the cycle: no plan; t's coefficient is its fit's, whose
  // 95 % interval holds the hidden drift.
  simulate_shipped(dir, "cycle", "--hidden t=0.002", "cycle.csv");
  const Json cycle = diagnose_json(dir, "cycle.csv");
  EXPECT_EQ(cycle["missing_effects"][0]["term"], "t") << cycle["verdict"];
  EXPECT_TRUE(cycle["missing_effects"][0]["significant"].get<bool>());
  EXPECT_TRUE(cycle["missing_effects"][0]["confounded_with"].empty());
  EXPECT_EQ(cycle["plan_command"], "");
  const Json f = fit_json(dir, "cycle.csv", "T + T^2 + dT + t");
  expect_gls_near_fit(cycle["missing_effects"][0], f["coefficients"]["t"].get<double>());
  expect_within_interval(f, "t", 0.002);
}

// When the candidates leave the model well above the floor, the verdict says
// that structure remains and where (a bump no candidate has the shape of).
TEST(DiagnoseBeyond, TheVerdictSaysWhenStructureRemains) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "clean.csv");
  // A 40-minute bump of 0.008 °/h centred at 3 h.
  rewrite(dir, "clean.csv", "bump.csv",
          [](double t) { return 0.008 * std::exp(-std::pow((t - 10800.0) / 1200.0, 2)); });
  const Json j = diagnose_json(dir, "bump.csv --candidates -step");
  EXPECT_FALSE(j["remaining"].get<std::string>().empty()) << j["verdict"];
  EXPECT_NE(j["verdict"].get<std::string>().find("structure remains"), std::string::npos) << j["verdict"];
}

}  // namespace
}  // namespace gyrotherm
