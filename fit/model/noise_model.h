#pragma once
// The gyro's noise as the fitter sees it: one model of the record, identified
// on the residual of the fitted model, from which every interval is computed.
//
// Each component is a process in continuous time whose window means have a
// covariance in closed form (window i: centre t_i, length Δ = the averaging
// window, samples covering a_i seconds):
//
//   white (ARW; quantisation is white at the windows too):
//       Var(m_i) = q_w / a_i,  N = √q_w / 60 °/√h  (σ_Allan(τ) = N/√τ_h).
//   flicker (bias instability): M Gauss–Markov processes of equal variance s²,
//       correlation times log-spaced two per decade from Δ to the record's
//       span (a 1/f spectrum between them, Barnes 1966); its Allan floor
//       B = s·max_τ √(Σ_i g(τ/τ_i)), g(x) = (2x − 3 + 4e^{−x} − e^{−2x})/x²
//       (sim/util/gauss_markov.h, shared with the simulator).
//   Gauss–Markov: variance σ², correlation time τ_c (free, Δ..span).
//   rate random walk: K (°/h/√h), q_r = K²/3600 (°/h)²/s.
//
// For a unit-variance exponential kernel e^{−|s|/τ} the window means have,
// with x = Δ/τ,
//   Var = 2 (τ/Δ)² (x − 1 + e^{−x}),   Cov_ij = (τ/Δ)² (2 sinh(x/2))² e^{−|t_i−t_j|/τ},
// and for a unit-rate random walk started at the record's start t₀ (s = t − t₀)
//   Var = s_i − Δ/6,   Cov_ij = min(s_i, s_j).
// Both are semi-separable, so C·X costs O(l·m) (forward and backward
// recursions), whatever the record's length.
//
// Identification: restricted maximum likelihood (REML) of the amplitudes and
// τ_c, with the model's regressors and the intercept as fixed effects, so the
// low-frequency power the regression absorbs is accounted for (Patterson &
// Thompson, Biometrika 58 (1971); as geodesy's Hector does for GNSS series:
// Bos, Fernandes, Williams & Bastos, J. Geodesy 87 (2013)). It runs on block
// means of consecutive windows (at most kIdentifyBlocks of them by default; the
// components' covariance of block means is exact), by Nelder–Mead from
// several starts with the overall scale profiled out. The amplitudes'
// uncertainty is the inverse REML expected information; a
// component whose amplitude the record cannot pin down is reported with an
// upper bound (where −2 log L has risen by 3.84).
//
// Coefficient intervals: the least-squares estimate's covariance under the
// identified covariance C (the sandwich (X̃ᵀX̃)⁻¹X̃ᵀCX̃(X̃ᵀX̃)⁻¹ on the centred
// design), with Student-t quantiles whose degrees of freedom carry the
// amplitudes' uncertainty (Satterthwaite, Biometrics Bull. 2 (1946)): a
// coefficient whose variance rests on a poorly known component (random walk
// over a short record) gets a wide interval, not a confident one.

#include <Eigen/Core>
#include <array>
#include <utility>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "fit/data/sensor_kind.h"

namespace gyrotherm::fit {

// The windows as the noise sees them.
struct WindowGrid {
  std::vector<double> time_s;       // centre (mean sample time) of each window, increasing
  std::vector<double> averaging_s;  // time the window's valid samples cover (white noise's averaging)
  double window_s = 0;              // the windows' length Δ
  std::size_t size() const { return time_s.size(); }
};

enum NoiseKind : int { kWhite = 0, kFlicker = 1, kGaussMarkov = 2, kRandomWalk = 3 };
inline constexpr int kNoiseKinds = 4;

// A component in physical units with its 95 % interval; a component the
// record cannot pin down has identified = false, lower = 0 and upper a bound.
struct NoiseParameter {
  std::string name;  // arw, bias_instability, gauss_markov, gauss_markov_tau, rrw
  std::string unit;
  double value = 0, lower = 0, upper = 0;
  bool identified = false;
};

struct NoiseModel {
  // White q_w ((°/h)²·s), flicker s² ((°/h)²), Gauss–Markov σ² ((°/h)²),
  // random walk q_r ((°/h)²/s).
  std::array<double, kNoiseKinds> amplitude{};
  double gm_tau_s = 0;
  std::vector<double> flicker_tau_s;
  double flicker_floor_per_s = 0;  // B / s of the bank
  // Covariance of θ = (q_w, s², σ², ln τ_c, q_r) from the REML expected
  // information; rows and columns of absent components are 0.
  Eigen::Matrix<double, 5, 5> covariance = Eigen::Matrix<double, 5, 5>::Zero();
  std::array<bool, kNoiseKinds> present{};     // in the model (amplitude not negligible)
  std::array<bool, kNoiseKinds> identified{};  // and pinned down by the record
  std::array<double, kNoiseKinds> upper_bound{};  // amplitude's 95 % bound where not identified
  // An absent Gauss–Markov process's 95 % bounds (τ_c in s, σ² in (°/h)²) at
  // correlation times log-spaced across the record's scales: having no τ_c
  // of its own, it is bounded at each (upper_bound[kGaussMarkov] is the one
  // at √(Δ·span)), and a test must hold under each (plausible_models).
  std::vector<std::pair<double, double>> gm_bounds;
  double minus_two_log_likelihood = 0;
  // Other structures (which components are in) that the record supports
  // about as well (Akaike's criterion within 2): intervals take the widest.
  std::vector<NoiseModel> alternatives;
  std::size_t blocks = 0;  // block means the identification used
  double block_s = 0;      // their typical length
  // The sensor whose noise this is (null: a gyro): the names and units of
  // parameters() and description(); the amplitudes are in its base unit.
  const SensorKind* sensor = nullptr;

  std::vector<NoiseParameter> parameters() const;
  // "white N = 3.1e-04 °/√h [2.8e-04, 3.4e-04]; flicker B = …; no random walk (K < …)"
  // `skip`: a component left out (one a report states elsewhere), or "".
  std::string description(std::string_view skip = {}) const;
  // The model's Allan variance ((°/h)²) at τ (s): q_w/τ + s²Σg(τ/τ_i) +
  // σ²g(τ/τ_c) + q_r τ/3, g the exponential kernel's (above).
  double allan_variance(double tau_s) const;
  // One draw of the windows' noise from the model (every component, each
  // window's mean): white N(0, q_w/a_i); each exponential kernel exactly (the
  // process simulated through each window and across the gaps, so the draws
  // have apply()'s covariance); the random walk at the window centres (its
  // within-window averaging, −q_r·Δ/6 of variance, neglected). `normal`
  // gives independent N(0, 1) draws.
  Eigen::VectorXd draw(const WindowGrid& grid, const std::function<double()>& normal) const;
  // C·x for the windows of `grid`: every component, or only `kind` at unit amplitude.
  Eigen::MatrixXd apply(const WindowGrid& grid, const Eigen::MatrixXd& x, int kind = -1) const;
  // The same into `y` (made x's shape, its storage reused when it has it).
  void apply(const WindowGrid& grid, const Eigen::MatrixXd& x, Eigen::MatrixXd& y, int kind = -1) const;
};

// A unit-variance exponential kernel e^{−|s|/τ} over windows of length Δ: the
// window means' variance and the factor A of Cov_ij = A·e^{−|t_i − t_j|/τ}
// (i ≠ j); both 2(τ/Δ)²(x − 1 + e^{−x}) and (τ/Δ)²(2 sinh(x/2))², x = Δ/τ.
struct ExpWindow {
  double diagonal, off;
};
ExpWindow exp_window(double tau, double delta);


// Identifies the noise of y − design·b (intercept included) by REML. Throws
// InputError when there are too few windows to say anything (fewer than
// design.cols() + 4), when the terms cannot be told apart at the block means,
// or when an amplitude comes out non-finite (nothing to trust).
// `most_blocks`: the block means it runs on. 64 serve the coefficients'
// intervals (results/ols_coverage.md: 92–98.5 %; 27 ms on a 72 h record);
// the step test, whose bootstrap draws noise window by window, needs the
// finer 128 (with 64 a step under Gauss–Markov noise was found in 7 of 10
// cycles, with 128 in 9).
inline constexpr std::size_t kIdentifyBlocks = 64;
NoiseModel identify_noise(const WindowGrid& grid, const Eigen::MatrixXd& design,
                          const Eigen::VectorXd& y, std::size_t most_blocks = kIdentifyBlocks);

// The noise models a test must hold under, since the record cannot tell
// which of them it is: the model identified, the other structures it
// supports about as well (alternatives), and the model with each slow
// component (flicker, Gauss–Markov, random walk) raised to the upper end of
// its two-sided 95 % interval (a one-sided 97.5 % bound; for a component not
// pinned down, its 95 % likelihood bound), the others held (an absent
// Gauss–Markov process at each correlation time of gm_bounds, at its bound there). A test whose p-value is the
// largest under all of them does not mistake noise the record could not pin
// down for an effect (diagnose, studies/diagnose/selection.cpp).
std::vector<NoiseModel> plausible_models(const NoiseModel& model, const WindowGrid& grid);

// The least-squares coefficients' covariance under the model, for the
// centred design `centred` (l × m), and each diagonal's Satterthwaite degrees
// of freedom (clamped to [1, l − m − 1]); each diagonal is the widest among
// the model and its alternatives.
struct NoiseSandwich {
  Eigen::MatrixXd covariance;
  std::vector<double> dof;
};
NoiseSandwich noise_sandwich(const NoiseModel& model, const WindowGrid& grid,
                             const Eigen::MatrixXd& centred);

// The same covariance under one model, kept in its parts so that any linear
// combination wᵀβ̂ has its variance and its own Satterthwaite dof (a band's
// point, a re-expanded coefficient: fit/model_band.h).
struct SandwichParts {
  SandwichParts(const NoiseModel& model, const WindowGrid& grid, const Eigen::MatrixXd& centred);
  Eigen::MatrixXd covariance;
  std::array<Eigen::MatrixXd, kNoiseKinds> unit_part;  // per unit amplitude
  Eigen::MatrixXd d_tau;                               // ∂/∂ln τ_c of the Gauss–Markov part
  std::array<double, kNoiseKinds> amplitude{};
  Eigen::Matrix<double, 5, 5> amplitude_covariance = Eigen::Matrix<double, 5, 5>::Zero();
  double max_dof = 1.0;  // l − m − 1
  double variance(const Eigen::VectorXd& w) const;
  double dof(const Eigen::VectorXd& w) const;  // clamped to [1, max_dof]
};
// The model's parts first, then each alternative's.
std::vector<SandwichParts> sandwich_parts(const NoiseModel& model, const WindowGrid& grid,
                                          const Eigen::MatrixXd& centred);

// A model with the windows it was identified on: what a LinearProblem carries.
struct NoiseContext {
  NoiseModel model;
  WindowGrid grid;
};

}  // namespace gyrotherm::fit
