// Results are data (docs/architecture.md, "House rules"): the diagnosis's
// and the fit engines' structs hold numbers, enums and names; sentences are
// composed by the renderers (studies/diagnose/diagnose_words.h,
// fit::interval_method_text). This scans the header for
// every text member and holds it to a list of names, so a field that would
// carry a sentence is stopped here, where the reviewer sees why.

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "cli_runner.h"

namespace gyrotherm {
namespace {

// Members declared as std::string or std::vector<std::string> in a header's structs.
std::set<std::string> text_members(const std::string& header) {
  std::ifstream in(testing::source_path(header));
  std::stringstream text;
  text << in.rdbuf();
  std::set<std::string> out;
  const std::regex member(R"(^\s*std::(?:vector<std::string>|string)\s+([A-Za-z_]\w*(?:\s*,\s*[A-Za-z_]\w*)*)\s*(?:=[^;]*)?;)");
  std::string line;
  for (std::istringstream lines(text.str()); std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, member)) continue;
    std::stringstream names(m[1].str());
    for (std::string name; std::getline(names, name, ',');) {
      name.erase(0, name.find_first_not_of(' '));
      name.erase(name.find_last_not_of(' ') + 1);
      out.insert(name);
    }
  }
  return out;
}

// Holds `header`'s text members to `names` (each with what it holds): a
// member not listed fails, with `rule` saying where its words belong.
void expect_text_members(const std::string& header, const std::map<std::string, std::string>& names,
                         const std::string& rule) {
  const std::set<std::string> found = text_members(header);
  for (const std::string& f : found)
    EXPECT_TRUE(names.count(f)) << header << ": the text member '" << f << "' is not a known name; " << rule;
  for (const auto& [name, why] : names) EXPECT_TRUE(found.count(name)) << name << " is gone: take it off the list";
}

TEST(ResultStructs, TheDiagnosisHoldsNamesNotSentences) {
  // Each text member and what it holds.
  const std::map<std::string, std::string> names = {
      {"candidates", "DiagnosisOptions: the terms, columns or 'step' the user named"},
      {"excluded_columns", "DiagnosisOptions: column names"},
      {"confounded_with", "term names"},
      {"name", "Skipped: a term or column name"},
      {"error", "Skipped: a FitError's message from the fit layer, quoted as thrown"},
      {"a", "ConfoundingEvidence: a term name"},
      {"b", "ConfoundingEvidence: a term name"},
      {"members", "term names"},
      {"columns_tried", "column names"},
  };
  std::set<std::string> expected;
  for (const auto& [name, why] : names) expected.insert(name);
  const std::set<std::string> found = text_members("studies/diagnose/diagnosis.h");
  for (const std::string& f : found)
    EXPECT_TRUE(expected.count(f)) << "studies/diagnose/diagnosis.h: the text member '" << f
                                   << "' is not a known name; a result holds numbers, enums and names, and "
                                      "sentences are composed in diagnose_words.cpp";
  for (const std::string& e : expected) EXPECT_TRUE(found.count(e)) << e << " is gone: take it off the list";
}

// The fit's summary as an engine returns it (fit/engines/engine.h): how its
// intervals were computed is an IntervalMethod (a kind and its numbers),
// rendered by interval_method_text(), and how the run went a RunDetail,
// rendered by run_text(); no member holds a sentence.
TEST(ResultStructs, TheFitResultHoldsItsIntervalMethodAsData) {
  const std::map<std::string, std::string> names = {
      {"engine", "FitResult: the engine's registry name"},
      {"term", "RunDetail::Step: a term name"},
      {"kept", "RunDetail: term names"},
      {"scope", "KeyValue: an engine name"},
      {"key", "KeyValue: an option name"},
      {"value", "KeyValue: an option value as given"},
      {"name", "EngineInfo: the registry name"},
      {"description", "EngineInfo: the registry's one-line description of the engine"},
  };
  expect_text_members("fit/engines/engine.h", names,
                      "how a result was computed is data (IntervalMethod, RunDetail), its words are "
                      "interval_method_text()'s and run_text()'s");
}

// The Allan coefficients (studies/allan/noise_coefficients.h): how each was
// read is a Reading and its numbers; coefficient_note() words it.
TEST(ResultStructs, TheAllanCoefficientsHoldNoSentence) {
  const std::set<std::string> found = text_members("studies/allan/noise_coefficients.h");
  for (const std::string& f : found)
    ADD_FAILURE() << "studies/allan/noise_coefficients.h: the text member '" << f
                  << "': a coefficient's reading is a Reading and numbers, worded by coefficient_note()";
}

// What a firmware export achieves (studies/export/firmware_outcome.h): the
// rule, the notes of a costly axis and the warnings are worded by its json(),
// lines(), notes() and warnings() from the firmware, each axis's FirmwareCost
// and the numbers.
TEST(ResultStructs, TheFirmwareOutcomeHoldsNamesNotSentences) {
  const std::map<std::string, std::string> names = {
      {"channel", "AxisOutcome: the fit's channel"},
      {"data", "FirmwareOutcome: the record's name"},
      {"fit_file", "FirmwareOutcome: a file name"},
      {"missing_data", "FirmwareOutcome: the data's name as the fit gives it"},
      {"dropped", "AxisOutcome: term names"},
  };
  expect_text_members("studies/export/firmware_outcome.h", names, "the outcome's words are its renderers'");
}

// The fit's warnings and the data's unit cautions: a NearCollinearity (the
// terms and the condition number) and a UnitCaution (a CautionKind, the
// numbers judged and the unit read), worded by fit::fit_warnings and
// fit::caution_text for every report, JSON and page.
TEST(ResultStructs, TheFitsWarningsAndTheDataCautionsAreData) {
  expect_text_members("fit/pipeline.h", {}, "a fit's warning is data, worded by fit_warnings()");
  expect_text_members("fit/model/linear_problem.h",
                      {{"terms", "NearCollinearity: term names"}, {"names_", "LinearProblem: term names"}},
                      "a warning is data, worded by near_collinearity_text()");
  expect_text_members("fit/data/plausibility.h",
                      {{"unit", "UnitCaution: a unit's name"},
                       {"unit_source", "UnitCaution: what chose the unit (a header, an option, a log format)"}},
                      "a caution is a CautionKind and numbers, worded by caution_text()");
  expect_text_members("fit/data/prepare.h", {{"file", "PreparedData: the record's name"}},
                      "the data's cautions are UnitCautions");
}

// A plan's result (studies/plan/): its notes are PlanNotes (a struct of
// numbers and names per kind), its thermal path a ThermalPath, its noise the
// PlanNoise itself, a baseline's shortfall its closest Precision (a Refusal
// and the standard errors), a target's source a TargetFrom; note_text,
// thermal_path_text, noise_text, baseline_why, refusal_text and
// target_from_text word them.
TEST(ResultStructs, ThePlanHoldsNamesNotSentences) {
  expect_text_members("studies/plan/plan.h",
                      {{"model", "PlanRequest: --model as given; PlanResult: a formula"},
                       {"se", "PlanRequest: --se values"},
                       {"rel_se", "PlanRequest: --rel-se values"},
                       {"separate", "PlanRequest: --separate values"},
                       {"param", "PlanRequest: --param values"},
                       {"prior", "PlanRequest: --prior values"},
                       {"scenario", "PlanRequest: a file name"},
                       {"rig", "PlanRequest: a file name"},
                       {"gyro", "PlanRequest: a file name"},
                       {"noise", "PlanRequest: a file name"},
                       {"out", "PlanRequest: a folder name"},
                       {"term", "TermPlan: a term name"},
                       {"unit", "TermPlan: a unit's name"},
                       {"rel_se_given", "TermPlan: the --rel-se value as given"},
                       {"recipe", "Baseline: the recipe's name"},
                       {"about", "Baseline: the recipe registry's description"},
                       {"scenario_file", "PlanResult: a file name"},
                       {"setpoint_file", "PlanResult: a file name"},
                       {"rig_file", "PlanResult: a file name"},
                       {"gyro_file", "PlanResult: a file name"},
                       {"figure_file", "PlanResult: a file name"}},
                      "a plan's words are its renderers' (plan.cpp, plan_notes.cpp)");
  expect_text_members("studies/plan/plan_notes.h",
                      {{"rig_file", "ThermalPath: a file name"},
                       {"scenario_file", "ThermalPath: a file name"},
                       {"name", "LooseNoise::Component: a noise component's name"},
                       {"unit", "LooseNoise::Component: its unit"},
                       {"file", "LooseNoise: a file name"},
                       {"term", "ParameterAssumed: a term name"},
                       {"parameter", "ParameterAssumed: the parameter's name"},
                       {"recipe", "RecipeIsPlan: the recipe's name"}},
                      "a note is data, worded by note_text()");
  expect_text_members("studies/plan/precision.h", {{"refused_terms", "Precision: term names"}},
                      "why a design is refused is a Refusal, worded by refusal_text()");
}

// The score baseline's check (studies/score/baseline.h): a regression is its
// engine, metric and both values with their intervals, a note a kind and the
// names it concerns; regression_text and baseline_note_text word them.
TEST(ResultStructs, TheBaselineCheckHoldsNamesNotSentences) {
  expect_text_members("studies/score/baseline.h",
                      {{"file", "Baseline: a file name"},
                       {"scenario", "Baseline: a file name"},
                       {"model", "Baseline: a formula"},
                       {"engine", "Regression: an engine name"},
                       {"metric", "Regression, BaselineNote: a metric's JSON field name"},
                       {"name", "BaselineNote: an engine or a file's role"}},
                      "the check's words are regression_text()'s and baseline_note_text()'s");
}

}  // namespace
}  // namespace gyrotherm
