// `gyrotherm fit`, `compensate`, `engines`, `effects` end to end, and the
// bad-input catalogue of the fitting issue: clear message, exit code 2.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.h"
#include "fit/fit_file.h"
#include "fit/engines/engine.h"
#include "sim/effects/effect.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

// A 3 h cycle segment (quick) simulated into dir/name.csv.
void simulate_short(const ScratchDir& dir, const std::string& name, int seed,
                    const std::string& extra = "") {
  write_text(dir / "short.toml",
             "name = \"short\"\nrig = \"" + source_path("scenarios/rig_shield.toml") +
                 "\"\ngyro = \"" + source_path("scenarios/gyro.toml") +
                 "\"\nstart_c = 20.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = 20.0\nduration_min = 30\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = 60.0\nrate_c_per_min = 5.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = 60.0\nduration_min = 60\n"
                 "[[segment]]\nkind = \"ramp\"\ntarget_c = -20.0\nrate_c_per_min = 5.0\n"
                 "[[segment]]\nkind = \"hold\"\ntemp_c = -20.0\nduration_min = 60\n");
  const auto r = run_cli(dir, "simulate short.toml --seed " + std::to_string(seed) + " " + extra +
                                  " -o " + name + ".csv");
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

TEST(CliFit, FitsSimulatedDataAndReportsAgainstTheTruth) {
  ScratchDir dir;
  simulate_short(dir, "run", 1);
  const auto r = run_cli(dir, "fit run.csv --json -o fit.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"engine", "model", "coefficients", "instability_before_dph",
                          "instability_after_dph", "ratio", "objective", "evaluations",
                          "iterations", "seconds", "termination", "history", "truth",
                          "coefficient_error"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["engine"], "ols");
  EXPECT_EQ(j["model"], "T + T^2 + dT");
  EXPECT_TRUE(j["coefficients"].contains("1"));
  EXPECT_GT(j["ratio"].get<double>(), 2.0);
  // dT/dt is the strongest effect here: recovered within a few percent.
  EXPECT_LT(std::abs(j["coefficient_error"]["dT"].get<double>()), 0.05);
  EXPECT_EQ(slurp(dir / "fit.json"), r.out);

  const auto human = run_cli(dir, "fit run.csv --engine iafsa --seed 3");
  ASSERT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("instability (std of 100 s averages)"), std::string::npos) << human.out;
  EXPECT_NE(human.out.find("truth 1.81"), std::string::npos) << human.out;
}

TEST(CliFit, ReportsTheIdentifiedNoiseAndWhatTheRecordCanSupport) {
  ScratchDir dir;
  simulate_short(dir, "run", 1);
  const auto r = run_cli(dir, "fit run.csv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("noise_model")) << r.out;
  const auto& components = j["noise_model"]["components"];
  for (const char* name : {"arw", "bias_instability", "gauss_markov", "rrw"}) {
    ASSERT_TRUE(components.contains(name)) << name;
    const auto& c = components[name];
    EXPECT_LE(c["interval_95"][0].get<double>(), c["interval_95"][1].get<double>()) << name;
    if (c["identified"].get<bool>()) {
      EXPECT_LE(c["interval_95"][0].get<double>(), c["value"].get<double>()) << name;
      EXPECT_GE(c["interval_95"][1].get<double>(), c["value"].get<double>()) << name;
    }
  }
  // The simulated white noise (ARW) is seen and named in its unit.
  EXPECT_TRUE(components["arw"]["identified"].get<bool>());
  EXPECT_EQ(components["arw"]["unit"], "deg/sqrt(h)");
  // A short record (under 200 windows): the default draws its intervals by the
  // parametric bootstrap; the analytic ones stay one option away.
  EXPECT_NE(j["interval_method"].get<std::string>().find("parametric bootstrap, 1000 draws"), std::string::npos)
      << j["interval_method"];
  const auto analytic = run_cli(dir, "fit run.csv --json --option intervals=model");
  ASSERT_EQ(analytic.exit_code, 0) << analytic.err;
  EXPECT_NE(nlohmann::json::parse(analytic.out)["interval_method"].get<std::string>().find("identified noise"),
            std::string::npos);
  ASSERT_TRUE(j.contains("record"));
  EXPECT_GE(j["record"]["temperature_levels"].get<int>(), 1);
  EXPECT_EQ(j["record"]["temp_range_c"], j["data"]["temp_range_c"]);
  // Newey-West stays one option away, and diagnose reports the same model.
  const auto nw = run_cli(dir, "fit run.csv --json --option intervals=nw");
  ASSERT_EQ(nw.exit_code, 0) << nw.err;
  EXPECT_NE(nlohmann::json::parse(nw.out)["interval_method"].get<std::string>().find("Newey-West"),
            std::string::npos);
  const auto d = run_cli(dir, "diagnose run.csv --json");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(nlohmann::json::parse(d.out)["noise_model"], j["noise_model"]);
  const auto text = run_cli(dir, "fit run.csv");
  EXPECT_NE(text.out.find("record: temperature"), std::string::npos) << text.out;
}

TEST(CliFit, CompensateAppliesTheFitToOtherData) {
  ScratchDir dir;
  simulate_short(dir, "train", 1);
  simulate_short(dir, "test", 2);
  ASSERT_EQ(run_cli(dir, "fit train.csv -o fit.json").exit_code, 0);
  const auto r = run_cli(dir, "compensate test.csv --fit fit.json -o comp.csv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["ratio"].get<double>(), 2.0);
  const std::string csv = slurp(dir / "comp.csv");
  EXPECT_NE(csv.find("time_s,temp_c,gyro_dph,model_dph,compensated_dph,outlier\n"),
            std::string::npos);
  const auto causal = run_cli(dir, "compensate test.csv --fit fit.json --causal --json");
  ASSERT_EQ(causal.exit_code, 0) << causal.err;
  EXPECT_EQ(nlohmann::json::parse(causal.out)["derivative"], "causal");
  EXPECT_GT(nlohmann::json::parse(causal.out)["ratio"].get<double>(), 1.5);
}

TEST(CliFit, EnginesAndEffectsList) {
  ScratchDir dir;
  const auto e = run_cli(dir, "engines --json");
  ASSERT_EQ(e.exit_code, 0);
  const auto engines = nlohmann::json::parse(e.out)["engines"];
  ASSERT_EQ(engines.size(), fit::engine_registry().size());
  for (std::size_t k = 0; k < engines.size(); ++k) EXPECT_EQ(engines[k]["name"], fit::engine_registry()[k].name);
  const auto f = run_cli(dir, "effects --json");
  ASSERT_EQ(f.exit_code, 0);
  const auto listed = nlohmann::json::parse(f.out)["effects"];
  ASSERT_EQ(listed.size(), effects::registry().size());
  const std::string text = run_cli(dir, "effects").out;
  for (std::size_t k = 0; k < listed.size(); ++k) {
    const effects::Effect& effect = *effects::registry()[k];
    EXPECT_EQ(listed[k]["term"], std::string(effect.name));
    EXPECT_EQ(listed[k]["needs"], effect.needs_temp2() ? "temp2_c" : "temp_c");
    EXPECT_EQ(listed[k].contains("parameter"), effect.parameter.has_value());
    EXPECT_NE(text.find(std::string(effect.meaning)), std::string::npos) << effect.name;
  }
}

struct BadFit {
  std::string name;
  std::string csv;   // written to d.csv ("" = none)
  std::string args;  // after "fit"
  std::vector<std::string> fragments;
};
void PrintTo(const BadFit& b, std::ostream* os) { *os << b.name; }

std::string rows(int n, const std::string& header = "time_s,temp_c,gyro_dph\n") {
  std::string s = header;
  for (int k = 0; k < n; ++k)
    s += std::to_string(k) + "," + std::to_string(20.0 + 0.01 * k) + ",-7.0\n";
  return s;
}

class CliFitBadInput : public ::testing::TestWithParam<BadFit> {};

TEST_P(CliFitBadInput, ClearMessageAndExitTwo) {
  const BadFit& c = GetParam();
  ScratchDir dir;
  if (!c.csv.empty()) write_text(dir / "d.csv", c.csv);
  const auto r = run_cli(dir, "fit " + c.args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  for (const std::string& f : c.fragments)
    EXPECT_NE(r.err.find(f), std::string::npos) << "stderr: " << r.err << "\nmissing: " << f;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, CliFitBadInput,
    ::testing::Values(
        BadFit{"missing_file", "", "nope.csv", {"nope.csv", "no such file"}},
        BadFit{"missing_column", "time_s,temp,gyro_dph\n0,1,2\n1,1,2\n", "d.csv",
               {"d.csv", "temp_c", "--temp-col"}},
        BadFit{"non_numeric_cell", "time_s,temp_c,gyro_dph\n0,20,-7\n1,abc,-7\n2,20,-7\n", "d.csv",
               {"d.csv:3", "temp_c", "abc"}},
        BadFit{"time_not_increasing", "time_s,temp_c,gyro_dph\n0,20,-7\n2,20,-7\n1,20,-7\n",
               "d.csv", {"d.csv:4", "time"}},
        BadFit{"nan_cell", "time_s,temp_c,gyro_dph\n0,20,-7\n1,20,nan\n2,20,-7\n", "d.csv",
               {"d.csv:3", "gyro_dph", "finite"}},
        BadFit{"too_few_points", rows(400), "d.csv", {"d.csv: only", "averaged points", "model"}},
        BadFit{"constant_temperature",
               [] {
                 std::string s = "time_s,temp_c,gyro_dph\n";
                 for (int k = 0; k < 3000; ++k) s += std::to_string(k) + ",25.0,-7.0\n";
                 return s;
               }(),
               "d.csv", {"d.csv: ", "constant"}},
        BadFit{"grad_without_temp2", rows(3000), "d.csv --model 'T + grad'",
               {"grad", "temp2_c", "--temp2-col"}},
        BadFit{"unknown_term", rows(3000), "d.csv --model 'T + T^7'",
               {"unknown term 'T^7'", "known terms"}},
        BadFit{"unknown_engine", rows(3000), "d.csv --engine ga", {"unknown engine 'ga'"}},
        BadFit{"invalid_engine_option", rows(3000), "d.csv --engine iafsa --option fish=0",
               {"iafsa option fish=0", "must be"}},
        BadFit{"unknown_engine_option", rows(3000), "d.csv --engine pso --option colour=red",
               {"pso has no option 'colour'"}},
        BadFit{"negative_budget", rows(3000), "d.csv --budget -5", {"--budget -5"}},
        BadFit{"bad_avg", rows(3000), "d.csv --avg 0", {"--avg"}}),
    [](const auto& param_info) { return param_info.param.name; });

TEST(CliFit, CompensateWithAMissingFitFile) {
  ScratchDir dir;
  write_text(dir / "d.csv", rows(3000));
  const auto r = run_cli(dir, "compensate d.csv --fit nofit.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nofit.json: no such file"), std::string::npos) << r.err;
}

TEST(CliFit, CompensateWithAMalformedFitFile) {
  ScratchDir dir;
  write_text(dir / "d.csv", rows(3000));
  write_text(dir / "fit.json", "{\"engine\": \"ols\", \"model\": \"T\"}");
  expect_refused(dir, "compensate d.csv --fit fit.json",
                 "fit.json: coefficients: missing (term -> value); is this a file written by 'gyrotherm fit -o'?");
  // A field inside an object is named by its path; an unknown term with the model.
  const std::pair<const char*, const char*> cases[] = {
      {R"({"engine": "ols", "model": "T", "coefficients": {"1": 0.5, "T": "x"}})",
       "fit.json: coefficients.T: must be a finite number (a model term's coefficient)"},
      {R"({"engine": "ols", "model": "T", "coefficients": {"1": 0.5}})",
       "fit.json: coefficients.T: missing (a model term's coefficient)"},
      {R"({"engine": "ols", "model": "T + T^9", "coefficients": {"1": 0.5}})",
       "fit.json: model 'T + T^9': unknown term 'T^9'"}};
  for (const auto& [text, expected] : cases) {
    write_text(dir / "fit.json", text);
    expect_refused(dir, "compensate d.csv --fit fit.json", expected);
  }
}

// The pipeline object written by to_json reads back by from_json to the same
// options; a field that is wrong is named by its path in the object.
TEST(CliFit, ThePipelineObjectRoundTripsAndNamesAFieldThatIsWrong) {
  fit::PipelineOptions p;
  p.averaging.window_s = 50.0;
  p.derivative = fit::DerivativeMode::causal;
  p.derivative_span_s = 900.0;
  p.sensor_tau_s = 12.5;
  p.remove_outliers = false;
  p.outliers.threshold = 6.0;
  p.columns.time = "t";
  p.columns.gyro = "gx,gy";
  p.columns.imu = 2;
  p.columns.csv = {.delimiter = "semicolon", .decimal_comma = true, .rate_hz = 0.0};
  p.columns.units.gyro = "rad/s";
  p.columns.units.gyro_scale = 0.5;
  p.columns.units.gyro_from = "--gyro-unit";
  const nlohmann::ordered_json written = p;
  const fit::PipelineOptions back = nlohmann::json::parse(written.dump()).get<fit::PipelineOptions>();
  nlohmann::ordered_json again = back, first = written;  // the same but for where the units came from
  again["columns"]["units"].erase("from");
  first["columns"]["units"].erase("from");
  EXPECT_EQ(again, first);
  EXPECT_EQ(back.columns.units.gyro_from, ", --gyro-unit when fitting");
  EXPECT_EQ(back.averaging.window_s, 50.0);
  EXPECT_EQ(back.derivative, fit::DerivativeMode::causal);
  EXPECT_EQ(back.sensor_tau_s, 12.5);
  EXPECT_EQ(back.columns.imu, 2);
  EXPECT_EQ(back.columns.csv.delimiter, "semicolon");
  EXPECT_TRUE(back.columns.csv.decimal_comma);
  EXPECT_EQ(back.columns.units.gyro_scale, 0.5);
  EXPECT_FALSE(back.columns.units.gyro_weak);  // an option's unit stays given
  EXPECT_TRUE(back.columns.units.time_weak);   // the default yields to the next record's header

  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  ASSERT_EQ(run_cli(dir, "fit d.csv --model T -o fit.json").exit_code, 0);
  nlohmann::json fit = nlohmann::json::parse(slurp(dir / "fit.json"));
  fit["pipeline"]["columns"]["csv"]["rate_hz"] = "fast";
  write_text(dir / "bad.json", fit.dump());
  const auto r = run_cli(dir, "compensate d.csv --fit bad.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad.json: pipeline.columns.csv.rate_hz: must be a finite number (Hz)"), std::string::npos)
      << r.err;
  fit["pipeline"]["columns"].erase("time");
  write_text(dir / "bad.json", fit.dump());
  EXPECT_NE(run_cli(dir, "compensate d.csv --fit bad.json").err.find("bad.json: pipeline.columns.time: missing (name)"),
            std::string::npos);
}

// Large logs (GYROTHERM_STREAM_ABOVE_MB=0 streams every file): fit, compensate
// and diagnose take the one-pass path, say so, and give what the in-memory
// path gives on a record within the streaming prefix.
TEST(CliFit, LargeLogPathsGiveTheInMemoryResults) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  const std::string stream = "GYROTHERM_STREAM_ABOVE_MB=0 ";
  const auto held = run_cli(dir, "fit c.csv -o held.json");
  const auto streamed = run_shell(dir, stream + "'" + GYROTHERM_CLI + "' fit c.csv -o streamed.json");
  ASSERT_EQ(streamed.exit_code, 0) << streamed.err;
  EXPECT_NE(streamed.out.find("samples (streamed)"), std::string::npos) << streamed.out;
  EXPECT_EQ(held.out.find("(streamed)"), std::string::npos);
  nlohmann::json fit_streamed = nlohmann::json::parse(slurp(dir / "streamed.json"));
  nlohmann::json fit_held = nlohmann::json::parse(slurp(dir / "held.json"));
  fit_streamed.erase("seconds");  // wall time
  fit_held.erase("seconds");
  EXPECT_EQ(fit_streamed, fit_held);

  for (const std::string mode : {"", " --causal"}) {
    ASSERT_EQ(run_cli(dir, "compensate c.csv --fit held.json -o held.csv" + mode).exit_code, 0);
    const auto c = run_shell(dir, stream + "'" + GYROTHERM_CLI + "' compensate c.csv --fit held.json -o streamed.csv" + mode);
    ASSERT_EQ(c.exit_code, 0) << c.err;
    EXPECT_EQ(slurp(dir / "streamed.csv"), slurp(dir / "held.csv")) << mode;
  }

  const auto d = run_shell(dir, stream + "'" + GYROTHERM_CLI + "' diagnose c.csv --json");
  const auto d_held = run_cli(dir, "diagnose c.csv --json");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  // The same windows, fit, floor and verdict; only the log's other columns
  // (chamber_c, case_c) are not tried as candidates.
  const nlohmann::json ds = nlohmann::json::parse(d.out), dh = nlohmann::json::parse(d_held.out);
  for (const char* key : {"instability_dph", "instability_before_dph", "noise_floor", "segments", "verdict"})
    EXPECT_EQ(ds[key], dh[key]) << key;
  std::size_t logged = 0;
  for (const auto& e : dh["missing_effects"]) logged += e["term"].get<std::string>().find("_c") != std::string::npos;
  EXPECT_GT(logged, 0u);
  EXPECT_EQ(ds["missing_effects"].size() + logged, dh["missing_effects"].size());
  const auto text = run_shell(dir, stream + "'" + GYROTHERM_CLI + "' diagnose c.csv");
  EXPECT_NE(text.out.find("read in one pass without holding the samples"), std::string::npos) << text.out;

  const auto bad = run_shell(dir, "GYROTHERM_STREAM_ABOVE_MB=lots '" + std::string(GYROTHERM_CLI) + "' fit c.csv");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("GYROTHERM_STREAM_ABOVE_MB=lots: expected a whole number of MB"), std::string::npos)
      << bad.err;
}

// The pagmo engines load libpagmo through a module at their first fit; a
// GYROTHERM_PAGMO_MODULE that names no module is the user's setting, refused
// naming it (exit 2, no output), and the engines without pagmo never load it.
TEST(CliFit, AWrongPagmoModulePathIsRefusedNamingIt) {
  testing::ScratchDir dir;
  testing::simulate_shipped(dir, "cycle", "", "c.csv");
  const std::string cli = std::string("GYROTHERM_PAGMO_MODULE=/nowhere/libgyrotherm_pagmo.so '") + GYROTHERM_CLI + "' ";
  const testing::CliResult refused = testing::run_shell(dir, cli + "fit c.csv --engine de -o de.json");
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_NE(refused.err.find("GYROTHERM_PAGMO_MODULE=/nowhere/libgyrotherm_pagmo.so: the pagmo engines (pso, de, "
                             "cmaes, abc) cannot load it"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "de.json"));
  EXPECT_EQ(testing::run_shell(dir, cli + "fit c.csv --engine ols").exit_code, 0);
}

}  // namespace
}  // namespace gyrotherm
