#pragma once
// `gls`: generalised least squares under the record's identified noise.
//
//   β̂ = (X̃ᵀC⁻¹X̃)⁻¹ X̃ᵀC⁻¹ỹ   on the design with its intercept column, C the
//   window means' covariance of the noise identified on the least-squares
//   residual (LinearProblem::noise(), fit/model/noise_model.h), applied in
//   O(l·r) by its semi-separable Cholesky factor (fit/model/noise_whitening.h).
//
// Where the noise has memory (flicker, Gauss–Markov, random walk) GLS weighs
// the windows as the noise makes them informative, and its intervals are
// narrower than least squares' under the same honest covariance (measured in
// results/ols_coverage.md). It does not minimise the paper's σ of eq. (6):
// its residual's σ is a little above ols's, by design.
//
// 95 % intervals: the estimate's variance under each noise structure the
// record supports alike (the identified model and its alternatives, as ols's
// sandwich takes them), Var = A C' Aᵀ with
// A = (X̃ᵀC⁻¹X̃)⁻¹X̃ᵀC⁻¹, the widest per coefficient (covariance=widest, the
// default) or the point model's alone (covariance=model); Student t with
// least squares' Satterthwaite degrees of freedom under the same noise.
// Without an identified noise (too few windows) it is ols, and says so.
//
// Reference: Kariya & Kurata, Generalized Least Squares (Wiley 2004), ch. 2;
// the covariance of a GLS estimate under a misspecified C, ibid. §2.5.

#include <string>

#include "fit/engines/engine.h"

namespace gyrotherm::fit {

struct GlsOptions {
  std::string covariance = "widest";  // widest (over the plausible noise models) or model

  void validate() const;
};

class GlsEngine : public Engine {
 public:
  explicit GlsEngine(GlsOptions options = {});
  FitResult fit(const LinearProblem& problem, FitObserver* observer = nullptr) const override;

 private:
  GlsOptions options_;
};

}  // namespace gyrotherm::fit
