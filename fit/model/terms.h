#pragma once
// A model's terms are the physical effects of the registry shared with the
// simulator (sim/effects/effect.h; `gyrotherm effects` lists them,
// docs/contracts.md fixes their names), and the fit's own terms below. A
// model is the intercept plus a list of terms; each term turns the window
// means' state (fit/data/derivatives.h) into one regressor, a column of the
// design matrix.
//
// Terms with a nonlinear parameter (hyst's dead band, warmup's time
// constant) get it fitted by variable projection (fit/pipeline.h).

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "fit/data/derivatives.h"
#include "sim/effects/effect.h"

namespace gyrotherm::fit {

using TermParameter = effects::EffectParameter;

// A term: a registry effect (its entry copied, `effect` pointing at it), or one
// of the fit's own terms below, which carry what only a fit knows (a log
// column, a step time) and compute their regressors here.
struct Term : effects::Effect {
  const effects::Effect* effect = nullptr;  // the registry entry; nullptr for the fit's own terms
  std::string_view column;                  // NAME and d(NAME): the log column
  bool column_rate = false;                 // d(NAME)
  double step_time_s = 0.0;                 // step@TIME

  // r at every window; `parameter` is θ (ignored without one).
  void compute(const DerivedSeries& series, double parameter, std::span<double> out) const;
};

// Every registry effect as a term, in registry order.
const std::vector<const Term*>& term_registry();
// A registry term by name; nullptr if unknown.
const Term* find_term(std::string_view name);

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
inline bool is_step_term(const Term* t) { return t->family == effects::Family::step; }
// A function of the temperature's level (a power of T, a filtered
// temperature), not of its rate or gradient: what the record's range
// supports (fit/record_support.h) and what is held at its edge.
inline bool reads_temperature_level(const Term* t) {
  return t->family == effects::Family::temperature_power || t->family == effects::Family::temperature_state;
}
// Whether a log column's name can be written as a term.
bool is_column_name(std::string_view name);
// "T, T^2, T^3, dT, ..."
inline std::string term_list() { return effects::names(); }

// Regressors of `terms` (parameters[i] used where the term has one), one column per term.
Eigen::MatrixXd design_matrix(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                              const std::vector<double>& parameters);

// The same with the temperature held within [lo_c, hi_c] for the terms that
// are a function of it (powers of T, a filtered temperature), as PX4 and
// ArduPilot hold their polynomial at TMIN/TMAX; rates, gradients, time and
// the log's columns see the record as it is.
Eigen::MatrixXd design_matrix_held(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                                   const std::vector<double>& parameters, double lo_c, double hi_c);
// The series those terms read there: its temperatures clamped to [lo_c, hi_c].
DerivedSeries held_within(const DerivedSeries& derived, double lo_c, double hi_c);

// Default parameters: the geometric mean of each parameter's bounds, NaN for
// terms without one.
std::vector<double> default_parameters(const std::vector<const Term*>& terms);

}  // namespace gyrotherm::fit
