#pragma once
// `stepwise`: stepwise regression as MATLAB's stepwisefit does it, the method
// the paper compares IAFSA with.
//
//   1. Start with no terms (the intercept only).
//   2. For every term outside the model, the p-value of its coefficient if it
//      were added; if the smallest is below p_enter (0.05), add that term and
//      go back to 2.
//   3. For every term in the model, the p-value of its coefficient; if the
//      largest is above p_remove (0.10), remove that term and go back to 2.
//   4. Otherwise stop; the kept terms get their least-squares coefficients, the
//      others 0.
//
// p-values are two-sided t-tests (t² is the partial F statistic) with
// l − k − 1 degrees of freedom under stepwisefit's assumption of independent
// residuals; every subset fit uses the correlation matrix G and c of
// fit/model/linear_problem.h: β_S = G_SS⁻¹ c_S, RSS = (l−1)(S_yy − c_Sᵀβ_S),
// Var β_j = RSS/(l−k−1) · (G_SS⁻¹)_jj/(l−1). Boost.Math gives the t
// distribution. On autocorrelated residuals the iid p-values are too small, so
// stepwise keeps more terms than it should; that is the method as published.
//
// Reference: Draper & Smith, Applied Regression Analysis (3rd ed.), ch. 15;
// MathWorks, stepwisefit documentation.

#include "fit/engines/engine.h"

namespace gyrotherm::fit {

struct StepwiseOptions {
  double p_enter = 0.05;   // a term enters when its p-value is below this
  double p_remove = 0.10;  // a term leaves when its p-value is above this, ≥ p_enter

  // Throws InputError naming the field, its value and the rule.
  void validate() const;
};

class StepwiseEngine : public Engine {
 public:
  explicit StepwiseEngine(StepwiseOptions options);
  FitResult fit(const LinearProblem& problem, FitObserver* observer = nullptr) const override;

 private:
  StepwiseOptions options_;
};

}  // namespace gyrotherm::fit
