// The requests the commands' options make (studies/options/*_options.h):
// the fields each option sets, the checks in the command line's order, and
// a fit made from keywords in process equals the one `gyrotherm fit` makes
// from the same options.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "fit/model/formula.h"
#include "studies/options/allan_options.h"
#include "studies/options/compensate_options.h"
#include "studies/options/diagnose_options.h"
#include "studies/options/export_options.h"
#include "studies/options/fit_options.h"
#include "studies/options/plan_options.h"
#include "studies/options/simulate_options.h"
#include "synthetic_log.h"

namespace gyrotherm::studies {
namespace {

using gyrotherm::testing::expect_input_error;

template <class O>
O from_keywords(const OptionTable<O>& table, const KeywordValues& given) {
  O o;
  apply_options(table, o, given);
  return o;
}

TEST(CommandOptions, FitRequestCarriesEveryOption) {
  const FitRequest r = fit_request(from_keywords(
      fit_option_table(), {{"data", "d.csv"}, {"model", "T + dT"}, {"add", "grad"}, {"engine", "pso"}, {"seed", "3"},
                           {"budget", "500"}, {"target", "0.01"}, {"option", "population=20"}, {"output", "f.json"},
                           {"avg", "50"}, {"deriv_span", "300"}, {"causal", "true"}, {"outlier_threshold", "5"},
                           {"gyro_col", "gx,gy"}, {"gyro_unit", "dps"}}));
  EXPECT_EQ(r.data, "d.csv");
  EXPECT_EQ(fit::formula_text(r.terms), "T + dT + grad");
  EXPECT_EQ(r.engine, "pso");
  EXPECT_EQ(r.settings.seed, 3u);
  EXPECT_EQ(r.settings.max_evaluations, 500);
  EXPECT_EQ(r.settings.target_objective, 0.01);
  EXPECT_EQ(r.settings.options.at("population"), "20");
  EXPECT_EQ(r.output, "f.json");
  EXPECT_EQ(r.pipeline.averaging.window_s, 50.0);
  EXPECT_EQ(r.pipeline.derivative_span_s, 300.0);
  EXPECT_EQ(r.pipeline.derivative, fit::DerivativeMode::causal);
  EXPECT_EQ(r.pipeline.outliers.threshold, 5.0);
  EXPECT_TRUE(r.pipeline.remove_outliers);
  EXPECT_EQ(r.pipeline.columns.gyro, "gx,gy");
  EXPECT_EQ(r.pipeline.columns.units.gyro, "dps");
  // The defaults are the command line's.
  const FitRequest d = fit_request(from_keywords(fit_option_table(), {{"data", "d.csv"}}));
  EXPECT_EQ(fit::formula_text(d.terms), fit::kDefaultModel);
  EXPECT_EQ(d.engine, "ols");
  EXPECT_EQ(d.settings.seed, 1u);
  EXPECT_EQ(d.pipeline.averaging.window_s, 100.0);
  EXPECT_EQ(d.pipeline.derivative, fit::DerivativeMode::central);
}

TEST(CommandOptions, FitChecksInTheCommandLinesOrder) {
  const auto refused = [](const KeywordValues& extra, const std::string& message) {
    KeywordValues given = {{"data", "d.csv"}};
    given.insert(given.end(), extra.begin(), extra.end());
    const FitCommandOptions o = from_keywords(fit_option_table(), given);
    expect_input_error([&] { fit_request(o); }, {message});
  };
  const KeywordValues contradiction = {{"keep_outliers", "true"}, {"outlier_threshold", "5"}};
  refused(contradiction, "--keep-outliers and --outlier-threshold contradict each other");
  KeywordValues bad_engine = contradiction;
  bad_engine.push_back({"engine", "ga"});
  refused(bad_engine, "unknown engine 'ga'");
  KeywordValues bad_term = bad_engine;
  bad_term.push_back({"add", "T^7"});
  refused(bad_term, "unknown term 'T^7'");
  refused({{"option", "colour=red"}, {"deriv_span", "30"}}, "ols has no option 'colour'");
  refused({{"budget", "-5"}}, "--budget");
  refused({{"gyro_unit", "deg/hr"}}, "--gyro-unit deg/hr: unknown unit");
  // A value outside its row's rule is refused as it is read, as the command
  // line does; the same rule holds an options struct built in code.
  for (const auto& [keyword, message] : std::vector<std::pair<std::string, std::string>>{
           {"deriv_span", "--deriv-span '0': must be > 0 s"},
           {"outlier_threshold", "--outlier-threshold '0': must be > 0"},
           {"sensor_tau", "--sensor-tau '-1': must be >= 0 s"}}) {
    const std::string value = keyword == "sensor_tau" ? "-1" : "0";
    expect_input_error([&] { from_keywords(fit_option_table(), {{"data", "d.csv"}, {keyword, value}}); }, {message});
  }
  FitCommandOptions built = from_keywords(fit_option_table(), {{"data", "d.csv"}});
  built.data_options.pipeline.derivative_span_s = -3.0;
  expect_input_error([&] { fit_request(built); }, {"--deriv-span '-3': must be > 0 s"});
}

TEST(CommandOptions, DiagnoseRequestKeepsTheModelAndTheAddedTermsApart) {
  const DiagnoseRequest r = diagnose_request(from_keywords(
      diagnose_option_table(), {{"data", "d.csv"}, {"model", "T + dT"}, {"add", "grad"}, {"add", "lag"}, {"seed", "4"},
                                {"candidates", "+supply_v,-T^2"}, {"plots", "figs"}, {"keep_outliers", "true"}}));
  EXPECT_EQ(fit::formula_text(r.base_terms), "T + dT");
  EXPECT_EQ(fit::formula_text(r.terms), "T + dT + grad + lag");
  EXPECT_EQ(r.added, (std::vector<std::string>{"grad", "lag"}));
  EXPECT_EQ(r.settings.seed, 4u);
  EXPECT_EQ(r.options.candidates, (std::vector<std::string>{"+supply_v", "-T^2"}));
  EXPECT_EQ(r.plots, "figs");
  EXPECT_FALSE(r.pipeline.remove_outliers);
  EXPECT_FALSE(r.progress);  // the caller's to give
  DiagnoseCommandOptions o = from_keywords(diagnose_option_table(), {{"data", "d.csv"}, {"engine", "ga"}, {"avg", "50"},
                                                                       {"keep_outliers", "true"}, {"outlier_threshold", "3"}});
  expect_input_error([&] { diagnose_request(o); }, {"unknown engine 'ga'"});
}

TEST(CommandOptions, AllanRequestChecksTheTausTheLongestTauAndTheConfidence) {
  const auto request = [](const KeywordValues& extra) {
    KeywordValues given = {{"data", "d.csv"}};
    given.insert(given.end(), extra.begin(), extra.end());
    return allan_request(from_keywords(allan_option_table(), given));
  };
  const AllanRequest r = request({{"taus", "decade"}, {"tau_max", "1000"}, {"ci", "0.95"}, {"plot", "a.png"},
                                  {"gyro_col", "gx"}, {"keep_outliers", "true"}});
  EXPECT_EQ(r.options.spacing, TauSpacing::decade);
  EXPECT_EQ(r.options.tau_max_s, 1000.0);
  EXPECT_EQ(r.options.confidence, 0.95);
  EXPECT_EQ(r.plot, "a.png");
  EXPECT_EQ(r.pipeline.columns.gyro, "gx");
  EXPECT_FALSE(r.pipeline.remove_outliers);
  EXPECT_EQ(request({}).options.spacing, TauSpacing::octave);
  expect_input_error([&] { request({{"taus", "weekly"}}); }, {"--taus 'weekly': must be one of octave, decade, all"});
  expect_input_error([&] { request({{"tau_max", "-1"}}); }, {"--tau-max '-1': must be >= 0 s"});
  expect_input_error([&] { request({{"ci", "1.2"}}); }, {"--ci '1.2': must be > 0 and < 1"});
  expect_input_error([&] { request({{"ci", "1"}}); }, {"--ci '1': must be > 0 and < 1"});
  expect_input_error([&] { request({{"deriv_span", "0"}}); }, {"--deriv-span '0': must be > 0 s"});
  AllanCommandOptions built = from_keywords(allan_option_table(), {{"data", "d.csv"}});
  built.taus = "hourly";
  expect_input_error([&] { allan_request(built); }, {"--taus 'hourly': must be one of octave, decade, all"});
  // With a fit the fit's own reading is used: the data options are not read.
  const AllanRequest with_fit = request({{"fit", "f.json"}, {"deriv_span", "30"}});
  EXPECT_EQ(with_fit.fit_file, "f.json");
  EXPECT_EQ(with_fit.pipeline.derivative_span_s, fit::PipelineOptions{}.derivative_span_s);
  EXPECT_FALSE(allan_option_table().rows.empty());
  for (const OptionRow<AllanCommandOptions>& row : allan_option_table().rows) EXPECT_NE(row.keyword, "avg");
}

TEST(CommandOptions, CompensateExportAndSimulateRequestsAreTheirOptions) {
  const CompensateRequest c = compensate_request(from_keywords(
      compensate_option_table(), {{"data", "d.csv"}, {"fit", "f.json"}, {"causal", "true"}, {"gyro_col", "gz"}}));
  EXPECT_EQ(c.fit_file, "f.json");
  EXPECT_TRUE(c.causal);
  EXPECT_EQ(c.columns.gyro, "gz");
  EXPECT_EQ(c.columns.temp, "");  // unset: the fit's
  const ExportRequest e = export_request(from_keywords(
      export_option_table(), {{"fit", "f.json"}, {"format", "px4"}, {"output", "p.params"}, {"instance", "2"}}));
  EXPECT_EQ(e.format, "px4");
  EXPECT_EQ(e.instance, 2);
  EXPECT_EQ(e.prefix, "gt_comp");
  const sim::SimulateRequest s = simulate_request(from_keywords(
      simulate_option_table(), {{"scenario", "s.toml"}, {"output", "o.csv"}, {"hidden", "grad=0.02"}, {"seed", "5"}}));
  EXPECT_EQ(s.hidden, (std::vector<std::string>{"grad=0.02"}));
  EXPECT_EQ(s.seed, 5u);
}

TEST(CommandOptions, PlanRequestTakesTheRangeAndTheDefaultScenario) {
  const plan::PlanRequest d = plan_request(PlanCommandOptions{}, "scenarios/cycle.toml");
  EXPECT_EQ(d.scenario, "scenarios/cycle.toml");
  EXPECT_FALSE(d.range_c);
  EXPECT_EQ(d.longest_h, 72.0);
  EXPECT_EQ(d.out, "plan");
  const plan::PlanRequest r = plan_request(
      from_keywords(plan_option_table(), {{"scenario", "mine.toml"}, {"range", "-20"}, {"range", "50"}, {"se", "T=1e-3,dT=0.1"}}),
      "scenarios/cycle.toml");
  EXPECT_EQ(r.scenario, "mine.toml");
  ASSERT_TRUE(r.range_c);
  EXPECT_EQ(r.range_c->first, -20.0);
  EXPECT_EQ(r.range_c->second, 50.0);
  EXPECT_EQ(r.se, (std::vector<std::string>{"T=1e-3", "dT=0.1"}));
  const PlanCommandOptions three = from_keywords(plan_option_table(), {{"range", "1,2,3"}});
  expect_input_error([&] { plan_request(three, "s.toml"); }, {"--range 1,2,3: expected two numbers LO,HI in °C"});
}

TEST(CommandOptions, AFitFromKeywordsIsTheCommandLinesFit) {
  testing::ScratchDir dir;
  std::string csv = "time_s,temp_c,gyro_dph\n";
  for (const testing::LogRow& row : testing::synthetic_log())
    csv += fmt::format("{},{},{}\n", row.t, row.temp_c, row.gyro_dph);
  testing::write_text(dir / "d.csv", csv);
  const std::string data = (dir / "d.csv").string();
  const testing::CliResult cli =
      testing::run_cli(dir, "fit '" + data + "' --model 'T + dT' --avg 50 --causal --seed 3 --outlier-threshold 6 --json");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  const FitRun run = run_fit(fit_request(from_keywords(
      fit_option_table(), {{"data", data}, {"model", "T + dT"}, {"avg", "50"}, {"causal", "true"}, {"seed", "3"},
                           {"outlier_threshold", "6"}})));
  nlohmann::json a = nlohmann::json::parse(cli.out), b = nlohmann::json::parse(run.json);
  a.erase("seconds");
  b.erase("seconds");
  EXPECT_EQ(a, b);
  EXPECT_EQ(a["pipeline"]["avg_s"], 50.0);
  EXPECT_EQ(a["pipeline"]["derivative"], "causal");
  EXPECT_EQ(a["pipeline"]["outlier_threshold"], 6.0);
}

}  // namespace
}  // namespace gyrotherm::studies
