#pragma once
// The candidates diagnose tries against a model (step 3 of
// studies/diagnose/diagnosis.h):
//
//  * every registered effect not in the model whose columns exist;
//  * every numeric column of the log, NAME, and its rate d(NAME): a quantity
//    the user logged (case or chamber temperature, supply voltage, field),
//    never the record's own time, temperature and gyro columns (all the
//    --gyro-col channels), nor the simulator's truth column bias_true_dph;
//  * the bias steps the model's residual shows (studies/diagnose/steps.h),
//    as step@TIME terms.
//
// --candidates changes the set: a list of names is exactly those (the word
// "step" for the steps found); entries starting with + or − add to or remove
// from the default set.

#include <cstdint>
#include <string>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/model/terms.h"
#include "studies/diagnose/steps.h"

namespace gyrotherm::studies {

struct CandidateSet {
  std::vector<const fit::Term*> terms;      // to be tried, registry first, then columns, then steps
  std::vector<std::string> skipped;    // what could not be a candidate, and why
  std::vector<StepCandidate> steps;    // the steps found in the residual
};

// The columns that are never candidates besides the record's own roles.
inline const std::vector<std::string> kNeverCandidates = {"bias_true_dph"};

// parameters: the model's fitted nonlinear parameters; seed: of the step
// test's bootstrap.
CandidateSet candidate_set(const fit::PreparedData& data, const std::vector<const fit::Term*>& model,
                           const std::vector<double>& parameters,
                           const std::vector<std::string>& requested,
                           const std::vector<std::string>& excluded_columns, std::uint64_t seed);

}  // namespace gyrotherm::studies
