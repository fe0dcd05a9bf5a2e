#pragma once
// Effects a record cannot tell apart (diagnose, step 3).
//
// Two terms whose regressors are nearly collinear over the windows,
// |corr(x_a, x_b)| > 0.99, explain the same part of the bias on this record:
// whichever a fit picks, the data do not say it is that one. A rate that is
// nearly constant (its standard deviation under 2 % of its mean: a steady
// ramp) cannot be told from the intercept "1". Such terms are grouped (transitively), and
// each group gets a sentence saying why, in the record's own terms (it only
// cools; the rate hardly changes; the range is narrow), and what test would
// separate them.
//
// The PAN log (cooling 24 → 16 °C at an almost constant rate) is the typical
// case: temperature and time correlate at −0.999, so a temperature effect
// cannot be told from a drift, and dT/dt is nearly constant, so a rate effect
// cannot be told from an offset.

#include <string>
#include <vector>

#include "fit/data/derivatives.h"
#include "fit/model/terms.h"
#include "fit/pipeline.h"

namespace gyrotherm::studies {

struct Confounding {
  std::vector<std::vector<std::string>> groups;  // term names ("1": the intercept)
  std::vector<std::string> notes;                // one sentence per group
  // The group holding `term`, or nullptr.
  const std::vector<std::string>* group_of(const std::string& term) const;
};

inline constexpr double kConfoundedCorrelation = 0.99;
inline constexpr double kNearlyConstant = 0.02;  // sd / |mean|

// Two candidates that are not collinear can still explain the same part of
// the bias (a fitted filter of T against the logged gradient): fitted together
// with the model (ols, its intervals under the record's identified noise,
// nonlinear parameters refitted), does each add significantly (95 %) to what
// the other explains? If neither does, the record cannot tell them apart; if
// only one does, it encompasses the other. Throws InputError when the joint
// model cannot be fitted.
struct Separation {
  bool a_adds = false, b_adds = false;
  std::string note;  // the sentence for a group, when neither adds
};
Separation separate(const fit::PreparedData& data, const std::vector<const fit::Term*>& model,
                    const fit::Term* a, const fit::Term* b);

// Adds a group {a, b} (merging with a group holding either) with its note.
void add_group(Confounding& c, const std::string& a, const std::string& b, const std::string& note);

// terms[i] at parameters[i] (NaN where it has none).
Confounding find_confounding(const fit::DerivedSeries& derived, const std::vector<const fit::Term*>& terms,
                             const std::vector<double>& parameters);

}  // namespace gyrotherm::studies
