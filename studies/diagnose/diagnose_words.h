#pragma once
// The words of a diagnosis: every sentence the text report and the JSON's
// sentence fields (verdict, confounding, remaining, skipped, next_command)
// say, composed here from the results' numbers and enums
// (studies/diagnose/diagnosis.h), once. No result struct holds a sentence;
// the renderers (diagnose_run.cpp for text, report.cpp for JSON, the Python
// package) read the data and, where they need words, these functions.

#include <string>
#include <vector>

#include "studies/diagnose/diagnosis.h"
#include "sim/util/option_table.h"

namespace gyrotherm::studies {

// How a next step is written: a command line, or a Python call (a record
// given as arrays has no file to name).
enum class CallStyle { command_line, python };

// "robust Hadamard deviation of the window means, 315 triples", or the within-window form.
std::string floor_description(const NoiseFloor& f);
// "45 % of the excess", or past the floor "all of the excess (103 %, below the estimated floor)".
std::string excess_share_text(double reduction_pct);
// A table cell: "45 %", or the words past the floor.
std::string share_cell(double reduction_pct);
// "T^3, T^4 and T^5" ("1" is "a constant offset").
std::string member_list(const std::vector<std::string>& members, const char* last = " and ");
// One line per group: "A and B cannot be told apart on this record: <why>; <the test that would separate them>."
std::string confounding_text(const ConfoundingGroup& g);
// "structure remains that no candidate explains: ..."
std::string remaining_text(const Remaining& r);
// What could not be tried, each reason once: "hyst (needs temp2_c); columns imu.acc.x, … (another motion sensor's channels, …)".
std::vector<std::string> skipped_texts(const std::vector<Skipped>& skipped);
// The verdict, one sentence: the effect, its size with interval, what it
// removes, or that nothing is significant; what the record cannot tell is
// named (its reasons are in confounding_text), what remains is appended.
std::string verdict_text(const Diagnosis& d);
// "gyrotherm diagnose FILE --model "…" [--gyro-col C] [the data options
// given]" or "gyrotherm.diagnose(data, model="…"[, gyro_col='C'][, time_col='t', …])".
std::string next_step_text(const std::string& record, const std::vector<const fit::Term*>& model,
                           const std::string& channel, CallStyle style,
                           const std::vector<GivenOption>& data_options = {});
// How the candidates were tested (diagnose --json's `significance`).
std::string significance_text(const DiagnosisOptions& options);
// "0.01 h", times since the record's start.
std::string hours_text(double seconds);
// A p-value to 2 significant digits, or to as many more (up to 6) as tell it
// from the level it was tested against: "0.0496" beside 0.05, not "0.05".
std::string p_text(double p, double level);

}  // namespace gyrotherm::studies
