#pragma once
// Bias steps (an RLG's mode hops) in the residual of a model (diagnose).
//
// The residual e_p of the window means after a least-squares fit with an
// intercept has zero mean; a step of size Δ at window k shows as a kink in its
// cumulative sum S_j = Σ_{i<j} e_i. Under no step, S_⌊un⌋ / (σ_LR √n) tends to a
// Brownian bridge (Ploberger & Krämer 1992, the OLS-CUSUM test), so
//
//     K = max_j |S_j| / (σ_LR √n)
//
// has the Kolmogorov distribution, P(K > x) = 2 Σ_{m≥1} (−1)^{m−1} e^{−2m²x²}.
// σ_LR² is the long-run variance of e, which autocorrelated residuals (flicker,
// a missing smooth effect) inflate: σ²(1 + ρ)/(1 − ρ) with ρ the lag-1
// autocorrelation (an AR(1) correction, ρ held below 0.9), so slow wander is
// not taken for a step.
//
// Where K's p-value is below α, the step is placed by least squares: the
// model's terms absorb part of a step (temperature follows time over a
// ramp), so the kink of the residual is not where the step is; the time whose
// step regressor u_k = 1{p ≥ k}, taken jointly with the model, removes the
// most residual variance, (eᵀũ_k)²/ũ_kᵀũ_k with ũ_k = u_k less its projection
// on the model, is (at least 4 windows a side). The step joins the model and
// the test runs again, up to max_steps.
//
// A step found here is only a candidate: diagnose scores it as the term
// step@TIME against the smooth candidates on the same footing (block
// cross-validation), so a smooth missing effect that also bends the CUSUM is
// not reported as a step unless a step explains the excess better.
//
// References: W. Ploberger, W. Krämer, "The CUSUM test with OLS residuals",
// Econometrica 60 (1992) 271–285; A. J. Scott, M. Knott, "A cluster analysis
// method for grouping means in the analysis of variance", Biometrics 30 (1974)
// (binary segmentation).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace gyrotherm::fit {

struct StepCandidate {
  double time_s = 0;       // between the last window before and the first after, since the record's start
  std::size_t index = 0;   // the first window after the step
  double p_value = 1;      // of the CUSUM test that found it
};

// time_s: window times since the record's start; design: the model's
// regressors (no intercept column); y: the window means. Steps in time order.
std::vector<StepCandidate> find_steps(const std::vector<double>& time_s, const Eigen::MatrixXd& design,
                                      const Eigen::VectorXd& y, double alpha = 0.01,
                                      std::size_t max_steps = 3);

// The spread of step sizes that noise alone fits: with the model and the step
// at `step_index` in `design` (no intercept column), the root mean square of
// the sizes fitted at every other possible step time at least 10 windows
// away (placebo steps). Slow noise (flicker wandering on the record's own
// scale) moves a step's fitted size far more than an autocorrelation-robust
// standard error admits; the placebos measure it on the record itself.
double placebo_step_sd(const Eigen::MatrixXd& design, const Eigen::VectorXd& y, std::size_t step_index);

// P(K > x) for the Kolmogorov distribution.
double kolmogorov_p(double x);

}  // namespace gyrotherm::fit
