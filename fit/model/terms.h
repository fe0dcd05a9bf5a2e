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

// Terms beyond the registry, made on first use and kept for the life of the
// process (so that a name always gives the same pointer):
//
//   step@TIME   0 before TIME, 1 from it on (TIME in s since the record's
//               first sample): a bias step, an RLG's mode hop;
//   NAME        the window means of the log's column NAME: a quantity the user
//               logged (case or chamber temperature, supply voltage, field);
//   d(NAME)     its rate, d(NAME)/dt, per second.
//
// A column name is a letter or '_' followed by letters, digits, '_' or '.'.
const Term* step_term(double time_s);
const Term* column_term(std::string_view column, bool rate);
// A registered term or one of the above, by name; nullptr if it is none.
const Term* term_by_name(std::string_view name);
inline bool is_column_term(const Term* t) { return !t->column.empty(); }
inline bool is_step_term(const Term* t) { return t->name.starts_with("step@"); }
// Whether a log column's name can be written as a term.
bool is_column_name(std::string_view name);
// "T, T^2, T^3, dT, ..."
inline std::string term_list() { return effects::names(); }

// Regressors of `terms` (parameters[i] used where the term has one), one column per term.
Eigen::MatrixXd design_matrix(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                              const std::vector<double>& parameters);

// Default parameters: the geometric mean of each parameter's bounds, NaN for
// terms without one.
std::vector<double> default_parameters(const std::vector<const Term*>& terms);

}  // namespace gyrotherm::fit
