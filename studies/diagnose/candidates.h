#pragma once
// The candidates diagnose tries against a model (step 3 of
// studies/diagnose/diagnosis.h):
//
//  * every registered effect not in the model whose columns exist;
//  * every numeric column of the log, NAME, and its rate d(NAME), when it
//    may be a cause (fit/data/column_role.h: a case or chamber temperature, a
//    supply voltage, a field), never the record's own time, temperature and
//    gyro columns (all the --gyro-col channels), nor the simulator's truth
//    column bias_true_dph, nor, unless named in --candidates, another motion
//    sensor's channel, a status word or a counter (they move with the
//    platform or the logger, not with the bias's physical causes);
//  * a bias step (an RLG's mode hop) at every position: one candidate, the
//    step family, whose grid is the positions (likelihood_test.h).
//
// --candidates changes the set: a list of names is exactly those (the word
// "step" for the step family, step@TIME for one step); entries starting with
// + or − add to or remove from the default set.

#include <string>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/model/terms.h"
#include "studies/diagnose/diagnosis.h"

namespace gyrotherm::studies {

struct CandidateSet {
  std::vector<const fit::Term*> terms;  // to be tried: registry first, then columns
  bool steps = false;                   // the step family is tried
  std::vector<Skipped> skipped;         // what could not be a candidate, and why
  std::vector<std::string> columns;     // the log's columns tried (each with its rate)
};

// The columns that are never candidates besides the record's own roles.
inline const std::vector<std::string> kNeverCandidates = {"bias_true_dph"};

CandidateSet candidate_set(const fit::PreparedData& data, const std::vector<const fit::Term*>& model,
                           const std::vector<std::string>& requested,
                           const std::vector<std::string>& excluded_columns);

}  // namespace gyrotherm::studies
