#pragma once
// `ols`: the exact least-squares optimum of the paper's eq. (6), the reference
// every other engine is scored against.
//
//   β̂ = argmin ‖ỹ − X̃β‖²   by column-pivoting Householder QR of the centred,
//   scaled design X̃ (never the normal equations), b_j = β̂_j / s_j, b0 = mean residual.
//
// 95 % confidence intervals. The residuals of 100 s averages are strongly
// autocorrelated (flicker noise, unmodelled slow effects), so the iid formula
// σ²(X̃ᵀX̃)⁻¹ would be far too narrow.
//
// Default (intervals=auto): the bootstrap below on a short record or under
// random-walk-dominated noise (bootstrap_by_default), else intervals=model.
// intervals=model: when the problem carries the record's
// identified noise (LinearProblem::noise(), fit/model/noise_model.h), the
// covariance is the sandwich (X̃ᵀX̃)⁻¹ X̃ᵀCX̃ (X̃ᵀX̃)⁻¹ with that noise's
// covariance C and Student-t quantiles with Satterthwaite dof per
// coefficient. Without one (too few windows), and with intervals=nw, the
// covariance is the Newey–West
// heteroscedasticity-and-autocorrelation-consistent (HAC) sandwich
//
//   V = (X̃ᵀX̃)⁻¹ S (X̃ᵀX̃)⁻¹,  S = Γ₀ + Σ_{ℓ=1..L} (1 − ℓ/(L+1)) (Γ_ℓ + Γ_ℓᵀ),
//   Γ_ℓ = Σ_p e_p e_{p−ℓ} x̃_p x̃_{p−ℓ}ᵀ,
//
// with the bandwidth L from Andrews' AR(1) plug-in rule for the Bartlett
// kernel: ρ = lag-1 autocorrelation of the residuals, α = 4ρ²/((1−ρ)²(1+ρ)²),
// L = ⌈1.1447 (α l)^{1/3}⌉ (capped at l/2), a small-sample factor l/(l−m−1),
// and Student-t quantiles with l − m − 1 degrees of freedom.
//
// Option intervals=bootstrap: a parametric bootstrap from the identified
// noise (fit/model/noise_bootstrap.h): `draws` draws, each from a noise model
// the record supports (structure by Akaike weight, amplitudes from their
// REML uncertainty), basic bootstrap intervals and p-values; from `seed`.
//
// Option intervals=ewc uses instead the equal-weighted cosine estimator
// (the scores projected on the B = ⌈0.4 l^{2/3}⌉ lowest cosine frequencies,
// Student t with B dof; Lazarus, Lewis, Stock & Watson, JBES 36 (2018)).
//
// Limits, measured in results/ols_coverage.md: neither kernel estimator can
// see noise whose memory is as long as the regressors' own time scale (the
// flicker of a gyro over a 9 h cycle): the regression absorbs that drift, the
// residuals look whiter than the noise was, and the intervals come out too
// narrow (62–80 % coverage); the identified noise model does not have that
// blind spot. A model that omits a real effect (the sensor lag's d2T) adds bias.
//
// References: Newey & West, Econometrica 55 (1987) 703–708; Andrews,
// Econometrica 59 (1991) 817–858; Golub & Van Loan, Matrix Computations §5.4.

#include <cstdint>
#include <string>
#include <vector>

#include "fit/engines/engine.h"

namespace gyrotherm::fit {

struct OlsOptions {
  std::string intervals = "auto";  // auto, model (identified noise), bootstrap, nw (Newey–West) or ewc
  int draws = 1000;                 // bootstrap draws
  std::uint64_t seed = 1;           // of the bootstrap (--seed)
  int ewc_terms = 0;  // cosine frequencies B for ewc; 0: ⌈0.4·l^{2/3}⌉ (LLSW's rule)

  // Throws InputError naming the field, its value and the rule.
  void validate() const;
};

class OlsEngine : public Engine {
 public:
  explicit OlsEngine(OlsOptions options = {});
  FitResult fit(const LinearProblem& problem, FitObserver* observer = nullptr) const override;

 private:
  OlsOptions options_;
};

// The exact optimum in unit-box coordinates (used by scoring and tests).
std::vector<double> least_squares_optimum(const LinearProblem& problem);

}  // namespace gyrotherm::fit
