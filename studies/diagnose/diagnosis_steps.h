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

// 3. Which effect is missing: every candidate tested under the record's
// identified noise and ranked greedily (d.candidates, d.first_round,
// d.skipped, d.noise); the pairs of candidates fitted together that the
// record cannot tell apart go to `inseparable`.
void rank_candidates(Diagnosis& d, const fit::PreparedData& data, const std::vector<const fit::Term*>& terms,
                     const DiagnosisOptions& options, std::vector<ConfoundingEvidence>& inseparable);

}  // namespace gyrotherm::studies::diagnosis_steps
