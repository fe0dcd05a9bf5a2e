#pragma once
// The whole `gyrotherm diagnose` job and its report, above the five steps of
// studies/diagnose/diagnosis.h: the model as given, and with --add the model
// without the added terms as the "before" of step 5; the `diagnose --json`
// object (docs/contracts.md's fields: model, instability_dph, noise_floor_dph,
// segments, missing_effects, verdict; and more) and the next command to run
// (or the test that would separate what the record cannot tell apart).

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "studies/diagnose/diagnose_words.h"
#include "studies/diagnose/diagnosis.h"

namespace gyrotherm::studies {

// What `gyrotherm plan` needs to separate the verdict's group (below).
struct PlanSuggestion {
  std::string model;
  std::vector<std::pair<std::string, double>> separate;  // member → size (NaN: unknown)
  std::vector<std::pair<std::string, double>> param;     // member → its fitted parameter
  double low_c = 0, high_c = 0;                          // the record's range, rounded outward
  // The group is confounded because its powers of T are nearly proportional
  // over that range: a test over it cannot separate them, so the command
  // leaves --range to the user's chamber (plan then takes its scenario's).
  bool range_too_narrow = false;
};
// gyrotherm plan --model … --separate … [--param …] --range …
std::string plan_command_text(const PlanSuggestion& p);

struct DiagnoseReport {
  std::vector<const fit::Term*> base_terms;  // the model without --add
  std::vector<const fit::Term*> terms;       // the model diagnosed
  std::string engine;
  Diagnosis diagnosis;
  std::optional<Diagnosis> before;      // with --add: the model without the added terms
  DiagnosisOptions options;             // as the diagnosis ran (its stage callback dropped)
  double start_time_s = 0;              // the record's first sample on the log's own clock
  std::string record;                   // the record's name, as a next step names it
  std::string channel;                  // with several gyro channels, this one's (else "")
  std::vector<GivenOption> data_options;  // the data options given (columns, units, --avg …), for a next step
  CallStyle style = CallStyle::command_line;  // how a next step is written (arrays: Python)
  std::optional<PlanSuggestion> plan;   // the test that would separate the verdict's group
};
// The next step (diagnosis.suggested), rendered in the report's style; "" when none.
std::string next_command(const DiagnoseReport& report);

// When the first candidate passed the test as one of a group this record
// cannot tell apart (the verdict says so): the `gyrotherm plan` command that
// designs a test on which each member, fitted with the model and the others,
// would be found,
//   gyrotherm plan --model 'MODEL' --separate A=SIZE,B=SIZE [--param A=θ] --range LO,HI
// SIZE: each member's coefficient added alone to the model (its unit);
// --param: a member's fitted nonlinear parameter (lag's time constant, …).
// Left out of --separate: "1" (the intercept) and the model's own terms (plan
// fits every member with the model anyway), a logged column and a step (no
// test not yet run can say what they will be). One member left (a group
// with the model's own terms or the intercept): plan separates it from
// them. "" when none is left, or otherwise.
// --range: the record's temperatures (window means, °C) rounded outward to
// this step, a range a chamber is commonly set to; a starting point only, the
// user sets the chamber's own (the report says so).
inline constexpr double kPlanRangeStepC = 5.0;
std::optional<PlanSuggestion> plan_suggestion(const Diagnosis& d, const std::vector<const fit::Term*>& terms,
                                              const fit::PreparedData& data);
inline std::string plan_command(const Diagnosis& d, const std::vector<const fit::Term*>& terms,
                                const fit::PreparedData& data) {
  const auto p = plan_suggestion(d, terms, data);
  return p ? plan_command_text(*p) : std::string();
}

// Throws InputError when the model already holds every term that could be
// tried on this data (nothing would be left to rank).
void check_something_left_to_try(const std::vector<const fit::Term*>& terms, const fit::PreparedData& data);

// `terms` is `base_terms` followed by the terms --add names (the caller
// parsed the whole formula, which refuses a term given twice).
DiagnoseReport diagnose_record(const fit::PreparedData& data, const fit::ColumnMap& columns,
                               const std::vector<const fit::Term*>& base_terms,
                               const std::vector<const fit::Term*>& terms, const fit::EngineInfo& engine,
                               const fit::EngineSettings& settings, const DiagnosisOptions& options = {});

nlohmann::ordered_json diagnosis_json(const DiagnoseReport& report);

}  // namespace gyrotherm::studies
