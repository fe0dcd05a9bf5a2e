#include "fit/model/linear_problem.h"

#include <Eigen/Dense>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "sim/util/format.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

LinearProblem::LinearProblem(Eigen::MatrixXd design, Eigen::VectorXd y,
                             std::vector<std::string> term_names, Collinear collinear)
    : design_(std::move(design)), y_(std::move(y)), names_(std::move(term_names)) {
  const Eigen::Index l = design_.rows();
  const Eigen::Index m = design_.cols();
  if (static_cast<Eigen::Index>(names_.size()) != m || y_.size() != l)
    throw std::invalid_argument("LinearProblem: sizes do not match");
  if (l < m + 2)
    throw FitError(fmt::format("only {} for a model with {} and an intercept: need at least {} (a longer "
                                 "record or a shorter --avg)",
                                 counted(static_cast<std::size_t>(l), "averaged point"),
                                 counted(static_cast<std::size_t>(m), "term"), m + 2));
  const double dof = static_cast<double>(l - 1);

  // Centre and scale (two-pass means and standard deviations).
  y_mean_ = y_.mean();
  y_centred_ = y_.array() - y_mean_;
  s_yy_ = y_centred_.squaredNorm() / dof;
  if (!(s_yy_ > 0.0))
    throw FitError("the gyro output is constant over the averaged data: there is nothing to "
                     "compensate (is the right column mapped with --gyro-col?)");
  mean_ = design_.colwise().mean().transpose();
  scaled_ = design_.rowwise() - mean_.transpose();
  scale_ = (scaled_.colwise().squaredNorm().transpose() / dof).cwiseSqrt();
  for (Eigen::Index j = 0; j < m; ++j) {
    const double relative = scale_[j] / std::max(1.0, std::abs(mean_[j]));
    if (!(scale_[j] > 0.0) || relative < 1e-12)
      throw FitError(fmt::format("the regressor of '{}' is constant over the data (it cannot be "
                                   "told apart from the intercept); drop it from the model or use "
                                   "data where it varies",
                                   names_[static_cast<std::size_t>(j)]));
    scaled_.col(j) /= scale_[j];
  }
  gram_ = scaled_.transpose() * scaled_ / dof;
  cross_ = scaled_.transpose() * y_centred_ / dof;


  // Conditioning of the correlation matrix: a large condition number means
  // some combination of terms is (almost) collinear on this data.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram_);
  const double lo = eig.eigenvalues().minCoeff();
  const double hi = eig.eigenvalues().maxCoeff();
  condition_ = lo > 0.0 ? hi / lo : std::numeric_limits<double>::infinity();
  if (condition_ > kPoorlyConditioned) {
    // Name the terms that make up the nearly null direction.
    const Eigen::VectorXd v = eig.eigenvectors().col(0);
    std::vector<std::string> terms;
    for (Eigen::Index j = 0; j < m; ++j)
      if (std::abs(v[j]) > 0.1) terms.push_back(names_[static_cast<std::size_t>(j)]);
    if (condition_ > kIllConditioned && (collinear == Collinear::refuse || !std::isfinite(condition_)))
      throw FitError(fmt::format(
          "the model's terms are collinear on this data ({}; condition number {:.3g} of the "
          "scaled design, above {:.0e}): their coefficients would be set by the noise, not by "
          "the data. Use data with a wider temperature range or more varied rates, or drop one "
          "of these terms",
          fmt::join(terms, ", "), condition_, kIllConditioned));
    near_collinearity_ = NearCollinearity{std::move(terms), condition_};
  }
  const Eigen::MatrixXd inverse = gram_.ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  half_width_ = 2.0 * std::sqrt(s_yy_) * inverse.diagonal().cwiseSqrt();
}

double LinearProblem::optimum_objective() const {
  const Eigen::VectorXd beta = gram_.ldlt().solve(cross_);
  std::vector<double> z(static_cast<std::size_t>(beta.size()));
  for (Eigen::Index j = 0; j < beta.size(); ++j) z[static_cast<std::size_t>(j)] = beta[j] / half_width_[j];
  return objective(z);
}

double LinearProblem::objective(std::span<const double> z) const {
  const Eigen::Index m = gram_.rows();
  // β = h ∘ z; σ² = S_yy − 2βᵀc + βᵀGβ.
  double quadratic = 0.0, linear = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const double bi = half_width_[i] * z[static_cast<std::size_t>(i)];
    linear += bi * cross_[i];
    double row = 0.5 * gram_(i, i) * bi;
    for (Eigen::Index j = 0; j < i; ++j) row += gram_(i, j) * half_width_[j] * z[static_cast<std::size_t>(j)];
    quadratic += 2.0 * bi * row;
  }
  return std::sqrt(std::max(0.0, s_yy_ - 2.0 * linear + quadratic));
}

double LinearProblem::objective_naive(std::span<const double> z) const {
  const Eigen::Index l = scaled_.rows(), m = scaled_.cols();
  double sum = 0.0;
  for (Eigen::Index p = 0; p < l; ++p) {
    double r = y_centred_[p];
    for (Eigen::Index j = 0; j < m; ++j)
      r -= scaled_(p, j) * half_width_[j] * z[static_cast<std::size_t>(j)];
    sum += r * r;
  }
  return std::sqrt(sum / static_cast<double>(l - 1));
}

Coefficients LinearProblem::physical(std::span<const double> z) const {
  Coefficients c;
  c.b.resize(dimension());
  c.intercept = y_mean_;
  for (std::size_t j = 0; j < dimension(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    c.b[j] = half_width_[jj] * z[j] / scale_[jj];
    c.intercept -= c.b[j] * mean_[jj];
  }
  return c;
}

std::vector<double> LinearProblem::unit_box(const Coefficients& c) const {
  std::vector<double> z(dimension());
  for (std::size_t j = 0; j < dimension(); ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    z[j] = c.b[j] * scale_[jj] / half_width_[jj];
  }
  return z;
}

Eigen::VectorXd LinearProblem::residuals(const Coefficients& c) const {
  Eigen::VectorXd r = y_.array() - c.intercept;
  for (std::size_t j = 0; j < dimension(); ++j) r -= c.b[j] * design_.col(static_cast<Eigen::Index>(j));
  return r;
}

double LinearProblem::sigma_two_pass(const Coefficients& c) const {
  const Eigen::VectorXd r = residuals(c);
  const double mean = r.mean();
  return std::sqrt((r.array() - mean).square().sum() / static_cast<double>(r.size() - 1));
}

std::string near_collinearity_text(const NearCollinearity& c) {
  return fmt::format(
      "{} are nearly collinear on this data (condition number {:.3g}): each coefficient alone is poorly "
      "determined, their combination is not; a wider temperature range separates them",
      fmt::join(c.terms, ", "), c.condition);
}

}  // namespace gyrotherm::fit
