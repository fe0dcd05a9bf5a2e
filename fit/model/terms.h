#pragma once
// The effect (term) registry: every physical effect a bias model can contain,
// by the names of DESIGN.md (a public contract). A model is the intercept plus
// a list of terms; each term turns the averaged series into one regressor.
//
//   T        T                          °C        temperature sensitivity
//   T^2      T²                         °C²       curvature of the sensitivity
//   T^3      T³                         °C³       higher-order curvature
//   dT       dT/dt                      °C/s      temperature-rate effect
//   T*dT     T·dT/dt                    °C²/s     rate sensitivity changing with temperature
//   d2T      d²T/dt²                    °C/s²     sensor-to-cavity thermal lag
//   grad     T₂ − T                     °C        gradient across the block (needs temp2_c)
//   hyst     +1 / −1 / 0 by dT/dt vs ±d  1         heating/cooling hysteresis (d fitted)
//   warmup   exp(−(t − t₀)/τ)           1         turn-on transient (τ fitted)
//   t        (t − t₀)/3600              h         slow drift, ageing
//
// T is the window mean of temp_c, t₀ the first sample's time. Derivatives are
// taken on the averaged series within each gap-free run: central differences
// (the default; one-sided at the ends of a run), or backward differences for a
// causal, real-time compensator (0 at the first window of a run).
//
// Terms with a nonlinear parameter (hyst's dead band, warmup's time constant)
// get it fitted by variable projection (fit/pipeline.h).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "fit/data/derivatives.h"

namespace gyrotherm::fit {

struct TermParameter {
  std::string name;      // e.g. "time_constant_s"
  double lower = 0.0;    // search bounds
  double upper = 0.0;
  bool log_scale = true;
};

struct Term {
  std::string name;
  std::string meaning;
  std::string unit;                    // of the regressor
  bool needs_temp2 = false;
  std::optional<TermParameter> parameter;
  // Regressor value per window (parameter ignored when the term has none).
  void (*regressor)(const DerivedSeries& d, double parameter, std::span<double> out) = nullptr;
};

const std::vector<Term>& term_registry();
// nullptr if unknown.
const Term* find_term(std::string_view name);
// "T, T^2, T^3, dT, T*dT, d2T, grad, hyst, warmup, t"
std::string term_list();

// Regressors of `terms` (parameters[i] used where the term has one), one column per term.
Eigen::MatrixXd design_matrix(const DerivedSeries& derived, const std::vector<const Term*>& terms,
                              const std::vector<double>& parameters);

// Default parameters: the geometric mean of each parameter's bounds, NaN for
// terms without one.
std::vector<double> default_parameters(const std::vector<const Term*>& terms);

}  // namespace gyrotherm::fit
