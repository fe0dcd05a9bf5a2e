#pragma once
// Candidates tested by likelihood under the record's identified noise
// (diagnose, step 3; studies/diagnose/diagnosis.h).
//
// With the windows whitened by the identified covariance C
// (fit/model/noise_whitening.h) and the current model [1, X] projected out,
// adding a candidate column x (a term at a value of its parameter, or a bias
// step at one position) removes the share
//
//     g(x) = (x̃ᵀẽ)² / (x̃ᵀx̃ · ẽᵀẽ)
//
// of the whitened residual ẽ (x̃: the whitened column less its projection on
// the model): the likelihood-ratio statistic with the scale profiled out is
// −ν·ln(1 − g), a monotone function of it (ν = l − m − 1, the residual's
// dimension). Under the null (the noise is C, x is not in the bias) ẽ is
// isotropic in that ν-dimensional space, so for one column g follows
// Beta(½, (ν − 1)/2) exactly:  p₁(g) = I_{1−g}((ν − 1)/2, ½).
//
// A candidate with a grid (a parameter's values, a step's positions) takes
// the largest g over it, G. Its p-value comes from B draws of isotropic noise
// (a parametric bootstrap from the identified noise: whitened, its draws are
// independent N(0, 1)), shared by every candidate, so the calibration does not
// multiply with their number: p₁ of each draw's maximum over the grid is
// Beta(1, n) when the grid amounts to n independent tests; n̂ is the rate of
// −ln(1 − p₁(max_b)) in the draws' lower tail (the maximum-likelihood rate of
// an exponential censored at the k-th smallest draw, k = B/20 and at least
// 10; n̂ ≥ 1; its spread about 1/√k, 22 % at B = 400, and about k/(k − 1)
// high, the conservative side: for correlated columns, a step's positions
// under white noise, the effective number grows as p falls, and from all
// draws n̂ came out too small), and
//
//     p = 1 − (1 − p₁(G))^n̂     (Šidák over n̂ tests),
//
// which, unlike the share of draws at least G, is not capped at 1/(B + 1):
// a loud effect gets the small p it deserves. The share of draws is kept as a
// check (p_bootstrap). Both hold exactly when the identified noise is the
// record's and the grid's columns independent; for a step under white noise
// the tail's p is as near the draws' share as 300 null records show
// (tests/likelihood_test_test.cpp); how far they hold under noise identified
// from the record itself is measured in results/diagnosis_power.md.
//
// The family: candidates are strongly correlated (a drift in time, a
// warm-up, a slow lag and a step late in the record remove much the same
// part), so a Bonferroni split of α over them is far stricter than the
// family-wise error needs. With each candidate's weight w_j (its share of
// α), the same draws give every candidate's p on each draw and so the
// draw's smallest p_j/w_j, Q_b; as for a grid, −ln(1 − Q_b) is
// exponential with rate W_eff, the family's effective number of tests
// (W_eff ≤ W = Σ w_j, equal when the candidates are independent; read from
// the draws' lower tail as n̂ is), and a
// candidate passes when p_j ≤ w_j·(1 − (1 − α)^{1/W_eff}) (Westfall & Young's
// min-p adjustment, in Šidák's form).
//
// References: R. H. Westfall, S. S. Young, "Resampling-based multiple
// testing" (Wiley 1993), ch. 2 (max-statistics over correlated tests);
// Z. Šidák, JASA 62 (1967) 626–633; T. Nyholt, Am. J. Hum. Genet. 74 (2004)
// 765–769 (an effective number of tests).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "fit/model/noise_whitening.h"

namespace gyrotherm::studies {

struct CandidateScore {
  double share = 0;          // G: the largest share of the whitened residual removed
  std::size_t best = 0;      // the grid column that removes it
  double p_value = 1;        // Šidák over the grid's effective number of tests
  double p_bootstrap = 1;    // (1 + #{draws ≥ G}) / (1 + B)
  double tests = 1;          // n̂, the grid's effective number of independent tests
  bool fitted = false;       // false: every column is collinear with the model
};

class LikelihoodTest {
 public:
  // model: the current model's regressors (no intercept column); y: the window means.
  LikelihoodTest(const fit::NoiseWhitener& whitener, const Eigen::MatrixXd& model, const Eigen::VectorXd& y);

  // A candidate's grid, one column per value (l × g), and its weight in the
  // family-wise correction; returns its index.
  std::size_t add(const Eigen::MatrixXd& columns, double weight = 1.0);
  // Draws the bootstrap (draws × windows independent normals from `seed`'s
  // stream, passed through the autoregression `ar` where it has
  // coefficients: residual_autoregression's) and scores every candidate added.
  void calibrate(int draws, std::uint64_t seed, const Eigen::VectorXd& ar = {});
  const CandidateScore& score(std::size_t candidate) const { return scores_[candidate]; }
  std::size_t candidates() const { return scores_.size(); }
  // W_eff: the family's effective number of tests (weighted; W = Σ w_j
  // before calibration or where the draws cannot tell).
  double family_tests() const { return family_tests_; }
  // ν = l − m − 1.
  double residual_dof() const { return dof_; }
  // The whitened, projected residual's squared norm (the model's −2 ln L part).
  double residual_rss() const { return rss_; }

  // p₁: the single-column null tail of a share g at ν residual dof.
  static double single_p(double share, double dof);

 private:
  const fit::NoiseWhitener& whitener_;
  Eigen::MatrixXd q_;        // orthonormal basis of the whitened [1, X]
  Eigen::VectorXd e_;        // the whitened residual
  double rss_ = 0, dof_ = 0;
  Eigen::MatrixXd columns_;  // every candidate's whitened, projected, unit-norm columns (valid ones)
  std::vector<std::size_t> owner_;  // candidate of each stored column
  std::vector<std::size_t> grid_index_;  // its index in the candidate's grid
  std::vector<CandidateScore> scores_;
  std::vector<double> weights_;
  double family_tests_ = 0;
};

// The whitened residual's own correlation at short lags, which the noise
// model, identified on block means, cannot see below a block's length: the
// autoregression of order ≤ most_order with the least Akaike criterion
// (Yule–Walker by Levinson–Durbin; empty when order 0 wins, as it does when
// the model whitens the windows). Drawn through it, the bootstrap carries
// that correlation into every candidate's null distribution: a sieve
// bootstrap of what the model leaves (P. Bühlmann, "Sieve bootstrap for
// time series", Bernoulli 3 (1997) 123–148).
Eigen::VectorXd residual_autoregression(const Eigen::VectorXd& whitened_residual, int most_order);

// The level a candidate of weight w is compared with in a family of W_eff
// effective tests: w·(1 − (1 − α)^{1/W_eff}).
double family_level(double alpha, double weight, double family_tests);

}  // namespace gyrotherm::studies
