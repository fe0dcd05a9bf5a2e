#pragma once
// What a chamber profile would teach the fitter (studies/plan/design_precision.h
// predicts it): each coefficient's standard error, or why the design
// identifies nothing.

#include <cstddef>
#include <string>
#include <vector>

namespace gyrotherm::studies::plan {

// se(ln θ) at which a nonlinear term's prediction is trusted: θ within
// about ±10 % (one standard error), where the regressor is close to linear in ln θ.
inline constexpr double kLogParameterSe = 0.1;

// Why a design identifies nothing; refusal_text words it.
enum class Refusal {
  none,                // the design is fitted
  too_short,           // fewer than kFewestWindows windows in the test
  too_few_windows,     // fewer windows than unknowns + 1
  constant_regressor,  // a term's regressor does not vary on the profile (refused_terms: it)
  collinear            // the terms' condition number above the fitter's limit (refused_terms: them)
};

struct Precision {
  double duration_s = 0;
  std::vector<double> se;  // per term, in the coefficient's unit; +∞ where not identified
  std::vector<double> log_parameter_se;  // per term: se of ln θ (NaN: no parameter or no prior)
  double condition = 0;    // of the scaled design's correlation matrix
  Refusal refusal = Refusal::none;        // why nothing is identified
  std::vector<std::string> refused_terms;  // the term names it concerns (see Refusal)
  std::size_t windows = 0;
  double sensor_min_c = 0, sensor_max_c = 0;
  bool refused() const { return refusal != Refusal::none; }
};

// "a test of 600 s has fewer than 8 windows", "T, T^2 are collinear on this
// profile (…)"; empty for a design that is fitted.
std::string refusal_text(const Precision& p);

}  // namespace gyrotherm::studies::plan
