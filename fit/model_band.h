#pragma once
// The covariance of a fitted model's coefficients, the intercept included,
// on the record it was fitted on, and from it the model's 95 % confidence
// band at each window (report's bias figure) and the interval of any linear
// combination of the coefficients (the firmware's re-expanded cubic).
//
// The covariance is the least-squares one under the record's identified noise
// (REML on the model's residual, fit/model/noise_model.h): the sandwich
// (XᵀX)⁻¹XᵀCX(XᵀX)⁻¹ of noise_sandwich on the centred, scaled design with a
// column of ones, carried to the physical coefficients. Each bound uses
// Student's t with the Satterthwaite dof of its own combination (as each
// coefficient's interval in the fit does): a coefficient's bound here is the
// fit's under intervals=model. The fitted parameters of
// nonlinear terms (a lag's τ) are held at their values: their own
// uncertainty is not in it (the fit's coefficient intervals, linearised, do
// carry it); docs/contracts.md says so.

#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "fit/model/noise_model.h"
#include "fit/pipeline.h"

namespace gyrotherm::fit {

struct CoefficientCovariance {
  // The least-squares covariance of p = (α, β), the centred, scaled design's
  // coefficients with the intercept, under the identified noise and each
  // alternative it supports about as well (fit/model/noise_model.h), and the
  // map to the physical θ = (b0, b_1..b_m) = A·p.
  std::vector<SandwichParts> parts;
  Eigen::MatrixXd to_physical;  // A
  // The 95 % interval's half width of Σ_j w_j·θ_j: under the noise model
  // that gives it the largest variance, with Student's t at that model's
  // Satterthwaite dof for this combination; `dof`, when given, receives it.
  double half_width(const Eigen::VectorXd& weights, double* dof = nullptr) const;
};

// Absent where the record has too few windows to identify its noise (the
// fit's intervals then come from Newey–West) or the design cannot be fitted.
std::optional<CoefficientCovariance> coefficient_covariance(const PreparedData& data,
                                                            const std::vector<const Term*>& terms,
                                                            const std::vector<double>& parameters);

// The band's half width at each window of `data` (its fitted value ± this),
// and the smallest dof among them.
struct Band {
  std::vector<double> half_width_dph;
  double smallest_dof = 0.0;
};
Band model_band(const CoefficientCovariance& covariance, const PreparedData& data,
                const std::vector<const Term*>& terms, const std::vector<double>& parameters);

}  // namespace gyrotherm::fit
