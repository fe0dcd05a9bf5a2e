#pragma once
// A model's terms are the physical effects of the registry shared with the
// simulator (sim/effects/effect.h; `gyrotherm effects` lists them, DESIGN.md
// fixes their names). A model is the intercept plus a list of terms; each
// term turns the window means' state (fit/data/derivatives.h) into one
// regressor, a column of the design matrix.
//
// Terms with a nonlinear parameter (hyst's dead band, warmup's time
// constant) get it fitted by variable projection (fit/pipeline.h).

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "fit/data/derivatives.h"
#include "sim/effects/effect.h"

namespace gyrotherm::fit {

using Term = effects::Effect;
using TermParameter = effects::EffectParameter;

// Every term, in registry order.
inline const std::vector<const Term*>& term_registry() { return effects::registry(); }
// nullptr if unknown.
inline const Term* find_term(std::string_view name) { return effects::find(name); }
// "T, T^2, T^3, dT, ..."
inline std::string term_list() { return effects::names(); }

// Regressors of `terms` (parameters[i] used where the term has one), one column per term.
Eigen::MatrixXd design_matrix(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                              const std::vector<double>& parameters);

// Default parameters: the geometric mean of each parameter's bounds, NaN for
// terms without one.
std::vector<double> default_parameters(const std::vector<const Term*>& terms);

}  // namespace gyrotherm::fit
