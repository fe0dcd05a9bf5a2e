#pragma once
// The steps of diagnose() (studies/diagnose/diagnosis.h) kept in files of
// their own; for diagnosis.cpp only.

#include <vector>

#include "studies/diagnose/candidates.h"
#include "studies/diagnose/diagnosis.h"

namespace gyrotherm::studies::diagnosis_steps {

// 2. Where it fails: the record's segments by its own temperature and the
// temperature bands, each with its residual RMS over the floor.
void locate_failures(Diagnosis& d, const fit::PreparedData& data);

// 3. Which effect is missing: every candidate scored by block cross-validation
// and ranked greedily (d.candidates, d.skipped, d.limited). Returns the bias
// steps the candidate set found, for sizing.
std::vector<StepCandidate> rank_candidates(Diagnosis& d, const fit::PreparedData& data,
                                           const std::vector<const fit::Term*>& terms,
                                           const DiagnosisOptions& options);

}  // namespace gyrotherm::studies::diagnosis_steps
