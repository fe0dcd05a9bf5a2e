#pragma once
// Effects a record cannot tell apart (diagnose, step 4).
//
// Two terms whose regressors are nearly collinear over the windows,
// |corr(x_a, x_b)| > 0.99, explain the same part of the bias on this record:
// whichever a fit picks, the data do not say it is that one. A rate that is
// nearly constant (its standard deviation under 2 % of its mean: a steady
// ramp) cannot be told from the intercept "1". Such terms are grouped
// (transitively), and each group carries why, in the record's own terms (it
// only cools, r(T, t); the rate hardly changes; the range is narrow), as data
// (ConfoundingEvidence, diagnosis.h); the renderers say it and name the test
// that would separate them.
//
// The PAN log (cooling 24 → 16 °C at an almost constant rate) is the typical
// case: temperature and time correlate at −0.999, so a temperature effect
// cannot be told from a drift, and dT/dt is nearly constant, so a rate effect
// cannot be told from an offset.

#include <string>
#include <vector>

#include "fit/data/derivatives.h"
#include "fit/model/terms.h"
#include "studies/diagnose/diagnosis.h"

namespace gyrotherm::studies {

inline constexpr double kConfoundedCorrelation = 0.99;
inline constexpr double kNearlyConstant = 0.02;  // sd / |mean|

// Adds the pair {e.a, e.b} (merging with every group holding either) with its evidence.
void add_group(std::vector<ConfoundingGroup>& groups, const ConfoundingEvidence& e);

// terms[i] at parameters[i] (NaN where it has none).
std::vector<ConfoundingGroup> find_confounding(const fit::DerivedSeries& derived,
                                               const std::vector<const fit::Term*>& terms,
                                               const std::vector<double>& parameters);

}  // namespace gyrotherm::studies
