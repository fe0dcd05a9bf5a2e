#pragma once
// The fitting problem every engine solves: the paper's eq. (6).
//
// Given l averaged points (100 s means) of the gyro output y_p and m model
// regressors x_pj (T, T², dT/dt, ...), find the coefficients b that minimise
// the standard deviation of the residual
//
//     r_p = y_p − Σ_j b_j x_pj,        σ(b) = sqrt( Σ_p (r_p − r̄)² / (l − 1) ),
//
// where the intercept b0 = r̄ (the mean residual) is not a search variable.
//
// Engines work in centred, scaled coordinates. With x̃_j = (x_j − x̄_j)/s_j
// (s_j the standard deviation of regressor j), ỹ = y − ȳ and β_j = b_j s_j,
//
//     σ²(β) = S_yy − 2 βᵀc + βᵀGβ,   G = X̃ᵀX̃/(l−1) (the correlation matrix),
//                                      c = X̃ᵀỹ/(l−1),  S_yy = ỹᵀỹ/(l−1),
//
// which costs O(m²) per evaluation whatever l is. Engines see the unit box
// z ∈ [−1, 1]^m with β_j = h_j z_j and half-widths
//
//     h_j = 2·sqrt(S_yy)·sqrt((G⁻¹)_jj)     (2·std(y)·√VIF_j),
//
// the smallest symmetric box that holds every coefficient vector doing at
// least as well as no compensation (σ(β) ≤ σ(0) is the ellipsoid
// (β−β*)ᵀG(β−β*) ≤ β*ᵀGβ* ≤ S_yy, whose extent along j is at most
// |β*_j| + sqrt(S_yy (G⁻¹)_jj) ≤ 2 sqrt(S_yy (G⁻¹)_jj)). The bounds come from
// the scale and correlation of the data, not from the least-squares answer.
//
// The Gram form loses digits when σ is far below std(y); the reported σ is
// recomputed from the residuals with a two-pass sum (sigma_two_pass).

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace gyrotherm::fit {

struct NoiseContext;  // fit/model/noise_model.h

// A model's coefficients in physical units: intercept b0 and b_j per term.
struct Coefficients {
  double intercept = 0.0;
  std::vector<double> b;
};

// What a LinearProblem does with nearly collinear terms: refuse them (a fit
// the user will read), or keep them unless exactly singular (a fit on part of
// the data, e.g. a cross-validation fold, whose predictions are all that is
// used).
enum class Collinear { refuse, keep };

// Terms so nearly collinear on the data (condition number of G above
// kPoorlyConditioned) that each coefficient alone is poorly determined,
// though their combination is not: a warning, worded by
// near_collinearity_text (the fit's JSON `warnings`, its text report).
struct NearCollinearity {
  std::vector<std::string> terms;  // the names along the nearly null direction
  double condition = 0.0;          // of G
};
std::string near_collinearity_text(const NearCollinearity& c);

class LinearProblem {
 public:
  // design: l × m regressors in physical units; y: the l averaged outputs.
  // Throws InputError if l ≤ m + 1, y or a regressor is constant, or the
  // design is ill-conditioned: the condition number of G above
  // kIllConditioned means some terms are so nearly collinear on this data that
  // their coefficients would be set by the noise (the message names the terms
  // and what to do); with Collinear::keep only a singular G is refused. Above
  // kPoorlyConditioned a warning is kept instead.
  LinearProblem(Eigen::MatrixXd design, Eigen::VectorXd y, std::vector<std::string> term_names,
                Collinear collinear = Collinear::refuse);

  std::size_t dimension() const { return static_cast<std::size_t>(design_.cols()); }
  std::size_t points() const { return static_cast<std::size_t>(design_.rows()); }
  const std::vector<std::string>& term_names() const { return names_; }

  // σ(z) in the units of y, from the Gram form: O(m²).
  double objective(std::span<const double> z) const;
  // The same σ by forming every residual: O(l·m) (reference and benchmark).
  double objective_naive(std::span<const double> z) const;
  // σ at the least-squares optimum from the normal equations of the scaled
  // design, O(m³) once the problem is built: for searches that compare many
  // designs (a nonlinear parameter's grid); ols itself solves by QR.
  double optimum_objective() const;

  Coefficients physical(std::span<const double> z) const;
  std::vector<double> unit_box(const Coefficients& c) const;
  // σ of y − b0 − Σ b_j x_j from the residuals, two-pass.
  double sigma_two_pass(const Coefficients& c) const;
  // The l residuals y − b0 − Σ b_j x_j.
  Eigen::VectorXd residuals(const Coefficients& c) const;
  // std(y) (l − 1 denominator): the instability before compensation.
  double sigma_y() const { return std::sqrt(s_yy_); }

  // For engines that need the data itself (ols, stepwise).
  const Eigen::MatrixXd& design() const { return design_; }
  const Eigen::VectorXd& y() const { return y_; }
  const Eigen::MatrixXd& scaled_design() const { return scaled_; }   // X̃
  const Eigen::VectorXd& centred_y() const { return y_centred_; }     // ỹ
  const Eigen::MatrixXd& gram() const { return gram_; }               // G
  const Eigen::VectorXd& cross() const { return cross_; }             // c
  const Eigen::VectorXd& scale() const { return scale_; }             // s_j
  const Eigen::VectorXd& half_width() const { return half_width_; }   // h_j
  double condition_number() const { return condition_; }              // of G
  // Terms nearly collinear on this data (absent: none): a warning, not a refusal.
  const std::optional<NearCollinearity>& near_collinearity() const { return near_collinearity_; }

  // The record's identified noise at these points (absent: none identified);
  // ols computes its intervals from it (fit/model/noise_model.h).
  void attach_noise(std::shared_ptr<const NoiseContext> noise) { noise_ = std::move(noise); }
  const NoiseContext* noise() const { return noise_.get(); }

  static constexpr double kIllConditioned = 1e6;
  static constexpr double kPoorlyConditioned = 1e3;

 private:
  Eigen::MatrixXd design_;
  Eigen::VectorXd y_;
  std::vector<std::string> names_;
  Eigen::VectorXd mean_, scale_, half_width_, cross_, y_centred_;
  Eigen::MatrixXd scaled_, gram_;
  double y_mean_ = 0.0;
  double s_yy_ = 0.0;
  double condition_ = 1.0;
  std::optional<NearCollinearity> near_collinearity_;
  std::shared_ptr<const NoiseContext> noise_;
};

}  // namespace gyrotherm::fit
