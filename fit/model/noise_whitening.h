#pragma once
// Generalised least squares under the record's identified noise, in O(l·r)
// per column: the window means' covariance C (fit/model/noise_model.h) is
// semi-separable, and its Cholesky factor is too.
//
// For windows n > m (times t_n > t_m) every component of C is a sum of
// products,
//     C_nm = Σ_j a_j e^{−(t_n − t_m)/τ_j}  +  q_r·s_m,
// the exponential kernels (flicker's bank, Gauss–Markov: a_j = amplitude ×
// the kernel's off-diagonal factor A) and the random walk (s = time since the
// record's start); the diagonal C_nn holds whatever is left (white q_w/a_n,
// the kernels' window variances, q_r(s_n − Δ/6)). Such a matrix factors as
// C = L D Lᵀ with L_nm = Ũ_nᵀ diag(Π_{k=m+1..n} φ_k) W_m, where, per
// component j, Ũ_nj = a_j (q_r), Ṽ_nj = 1 (s_n), φ_nj = e^{−(t_n − t_{n−1})/τ_j}
// (1), by the recursion (S_1 = 0)
//     S_n = diag(φ_n) (S_{n−1} + D_{n−1} W_{n−1} W_{n−1}ᵀ) diag(φ_n),
//     D_n = C_nn − Ũ_nᵀ S_n Ũ_n,       W_n = (Ṽ_n − S_n Ũ_n) / D_n,
// O(l·r²) once; then the whitened x, z = D^{−1/2} L^{−1} x, is the forward
// substitution z_n = x_n − Ũ_nᵀ f_n, f_n = φ_n ∘ (f_{n−1} + W_{n−1} z_{n−1}),
// O(l·r) per column, and log|C| = Σ ln D_n. GLS is then least squares on
// the whitened design and output.
//
// Reference: D. Foreman-Mackey, E. Agol, S. Ambikasaran, R. Angus, "Fast and
// scalable Gaussian process modeling with applications to astronomical time
// series", AJ 154 (2017) 220, §5 (the same recursion, there with damped
// cosines; here real exponentials and a random walk's min(s_n, s_m)).

#include <Eigen/Core>
#include <vector>

#include "fit/model/noise_model.h"

namespace gyrotherm::fit {

class NoiseWhitener {
 public:
  // Throws FitError when the covariance is not positive definite at these
  // windows (a model with no white noise on windows of equal times, say).
  NoiseWhitener(const NoiseModel& model, const WindowGrid& grid);

  // D^{−1/2} L^{−1} x, column by column: white with unit variance when x is
  // drawn from the model.
  Eigen::MatrixXd whiten(const Eigen::MatrixXd& x) const;
  Eigen::VectorXd whiten(const Eigen::VectorXd& x) const;
  // C⁻¹x: the whitening above, then L⁻ᵀ by the backward recursion
  // (g_l = 0, g_m = φ_{m+1} ∘ (g_{m+1} + Ũ y_{m+1}), y_m = w_m − W_mᵀ g_m).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& x) const;
  // log |C|.
  double log_determinant() const;
  std::size_t size() const { return d_.size(); }

 private:
  Eigen::VectorXd a_;  // Ũ, one per component (constant over the windows)
  std::vector<bool> random_walk_;  // component j is the random walk (Ṽ = s, φ = 1)
  Eigen::VectorXd rate_;           // 1/τ_j of the kernels (0 for the random walk)
  std::vector<double> time_s_, since_s_;
  std::vector<double> d_;          // D_n
  Eigen::MatrixXd w_;              // W_n, r × l
};

// Generalised least squares of y on [1, x] (the intercept first): the
// coefficients, their covariance (XᵀC⁻¹X)⁻¹ and the whitened residual.
struct GlsFit {
  Eigen::VectorXd beta;          // intercept, then one per column of x
  Eigen::MatrixXd covariance;    // of beta, under the model
  Eigen::VectorXd whitened_residual;
  double log_likelihood = 0;     // Gaussian, at beta, with the model as given
};
GlsFit gls(const NoiseWhitener& whitener, const Eigen::MatrixXd& x, const Eigen::VectorXd& y);

// The variance of coefficient k (0: the intercept) of GLS on [1, x], the
// widest over `whiteners` (one per noise model the record supports alike,
// fit::plausible_models): since the record cannot tell which holds, an
// interval from the narrowest would claim more than it shows.
double widest_variance(const std::vector<NoiseWhitener>& whiteners, const Eigen::MatrixXd& x, Eigen::Index k);

}  // namespace gyrotherm::fit
