#pragma once
// Bias steps (an RLG's mode hops) in the residual of a model (diagnose).
//
// A step of size Δ after window k adds Δ·u_k to the window means, with
// u_k = 1{p ≥ k}. Taken jointly with the model (least squares: the model's
// terms absorb part of a step, since temperature follows time over a ramp, so
// the kink of the residual is not where the step is), the step at k removes
//
//     G_k = (eᵀũ_k)² / ũ_kᵀũ_k,   ũ_k = u_k less its projection on the model,
//
// of the residual sum of squares eᵀe. The step is placed where G_k is
// largest (at least 4 windows a side), and the statistic is the share it
// removes, R = max_k G_k / eᵀe.
//
// Is that step more than noise? The noise of a gyro's window means is not
// white: flicker (bias instability) and random walk wander on the record's
// own time scale, and over a long record such wander fits a step as well as a
// small real step does. Two tests tried first failed on our own records: the
// OLS-CUSUM test with an AR(1) long-run variance called a step in 3 of 10
// clean 64-hour records, and the share R compared with phase-randomised
// surrogates of the residual never found a large step (the step, left in the
// residual, is read as slow noise and makes its own null: a 13-σ step in
// white noise was found in 1 of 20 records; the long-run variance estimated
// under the null has the same non-monotone power, Vogelsang 1999).
//
// So the noise is modelled, and a step is tested against it. The local level
// model y_t = μ_t + ε_t, μ_{t+1} = μ_t + η_t, var η = q·var ε, is white noise
// plus a random walk: it can wander as slow noise does, but only by many
// small moves, while a step is one large move. Its Kalman filter whitens the
// series (innovations v_t/√F_t); a step before window k whitens to
// w_k(t) = L_k···L_{t−1}/√F_t, so its GLS t-statistic jointly with the
// model's whitened regressors follows the smoother's backward recursions
// (r, N) in O(l·columns) for every k at once (without a model it is the
// standardised smoothed level disturbance, Harvey & Koopman 1992, the
// intervention t-test of de Jong & Penzer 1998). The statistic is
// T = max_k |t_k|. q is fitted by maximum likelihood to the residual with
// its best step taken out (under the alternative: a step left in would be
// fitted as a large q and hide itself).
//
// The p-value is a parametric bootstrap, (1 + #{T* ≥ T}) / (1 + replicates),
// with T* found the same way on series drawn from the record's own noise
// model and projected off the model like the residual: the noise identified
// by REML (fit/model/noise_model.h: white, flicker, Gauss–Markov, random walk)
// on the windows with the model and the best step as fixed effects (under
// the alternative, so the step is not read as slow noise). Gauss–Markov
// noise then neither hides a step (a local level model reads it as a random
// walk, whose wander makes every step look ordinary) nor invents one. Where
// the noise cannot be identified (too few windows) the draws come from the
// fitted local level model, as before. It holds its level on
// white noise and random walks; on flicker spanning the record's own scale
// (synthetic, three decades) it calls a step in about 7 % of records at
// α = 0.01, because flicker makes larger single moves than a random walk of
// the same spread. results/diagnosis_false_alarms.md measures the rate on
// simulated gyro records, and diagnose adds a second gate: a step must also
// beat every smooth candidate in block cross-validation.
//
// Found, the step joins the model and the search runs again, up to
// max_steps (forward selection, as in binary segmentation). Like binary
// segmentation it can miss a hop and a hop back: with one taken out, the
// other inflates q and neither stands out (on 200 white windows, a ±4 σ pair
// 80 windows apart is missed; ±6 σ is found). Taking out the best two steps
// before fitting q finds such pairs but calls steps in 38 % of flicker
// records; no remedy tried keeps both.
//
// A step found here is only a candidate: diagnose scores it as the term
// step@TIME against the smooth candidates on the same footing (block
// cross-validation), so a smooth missing effect that also bends the residual
// is not reported as a step unless a step explains the excess better.
//
// References: A. C. Harvey, S. J. Koopman, "Diagnostic checking of
// unobserved-components time series models", J. Business & Economic
// Statistics 10 (1992) 377–389; P. de Jong, J. Penzer, "Diagnosing shocks in
// time series", JASA 93 (1998) 796–806; J. Durbin, S. J. Koopman, "Time
// Series Analysis by State Space Methods" (2nd ed., 2012), ch. 2 (local level
// filter and smoother); T. J. Vogelsang, "Sources of nonmonotonic power when
// testing for a shift in mean of a dynamic time series", J. Econometrics 88
// (1999) 283–299; A. J. Scott, M. Knott, "A cluster
// analysis method for grouping means in the analysis of variance", Biometrics
// 30 (1974) 507–512 (binary segmentation).

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "fit/model/noise_model.h"
#include "sim/util/random.h"

namespace gyrotherm::studies {

struct StepCandidate {
  double time_s = 0;       // between the last window before and the first after, since the record's start
  std::size_t index = 0;   // the first window after the step
  double p_value = 1;      // of the bootstrap test that found it
};

struct StepSearch {
  double alpha = 0.01;          // a step is kept when its bootstrap p-value is below this
  // The windows as the noise model sees them: with them the bootstrap draws
  // from the record's identified noise (below); without, from the local level model.
  const fit::WindowGrid* grid = nullptr;
  std::size_t max_steps = 3;
  int replicates = 199;         // of the bootstrap; the p-value's resolution is 1/(1 + replicates)
  std::uint64_t seed = 1;       // of the bootstrap's draws
};

// time_s: window times since the record's start; design: the model's
// regressors (no intercept column); y: the window means. Steps in time order.
std::vector<StepCandidate> find_steps(const std::vector<double>& time_s, const Eigen::MatrixXd& design,
                                      const Eigen::VectorXd& y, const StepSearch& search = {});

// The ratio q = var η / var ε of the local level model fitted to y by
// maximum likelihood (σ² concentrated out, Brent's method on log q over
// [1e-8, 1e2], the first observation starting the level).
double fit_level_q(const Eigen::VectorXd& y);

// The GLS t-statistic of a level shift before each window k of y, jointly
// with the columns of `model` (an intercept column is allowed: it whitens to
// nothing), under the local level model with ratio q; 0 where no step is
// placed (fewer than 4 windows a side).
Eigen::VectorXd level_shift_t(const Eigen::VectorXd& y, const Eigen::MatrixXd& model, double q);

// T = max_k |t_k| for a residual e orthogonal to the orthonormal columns of q
// (the model with its intercept), q fitted to e less its best step.
double level_shift_statistic(const Eigen::VectorXd& e, const Eigen::MatrixXd& q);

// The bootstrap p-value of T for noise fitted on `noise` (a residual without
// its best step) by the local level model, or drawn from `model` on `grid`.
double level_shift_p(const Eigen::VectorXd& noise, const Eigen::MatrixXd& q, double statistic, int replicates,
                     Rng& rng, const fit::NoiseModel* model = nullptr, const fit::WindowGrid* grid = nullptr);

// The spread of step sizes that noise alone fits: with the model and the step
// at `step_index` in `design` (no intercept column), the root mean square of
// the sizes fitted at every other possible step time at least 10 windows
// away (placebo steps). Slow noise (flicker wandering on the record's own
// scale) moves a step's fitted size far more than an autocorrelation-robust
// standard error admits; the placebos measure it on the record itself.
double placebo_step_sd(const Eigen::MatrixXd& design, const Eigen::VectorXd& y, std::size_t step_index);

}  // namespace gyrotherm::studies
