#include "studies/plan/design_precision.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <limits>

#include "fit/data/prepare.h"
#include "fit/model/linear_problem.h"
#include "fit/pipeline.h"
#include "sim/simulator.h"
#include "sim/util/numbers.h"

namespace gyrotherm::studies::plan {

namespace {

constexpr double kLogStep = 1e-4;  // the fitter's step in ln θ (fit/pipeline.h)
constexpr double kFewestWindows = 8;  // a shorter profile is not a test

}  // namespace

DesignEvaluator::DesignEvaluator(sim::Scenario base, sim::RigConfig rig, sim::GyroConfig gyro,
                                 PlanNoise noise, PlanModel model)
    : base_(std::move(base)), rig_(std::move(rig)), gyro_(std::move(gyro)), noise_(std::move(noise)),
      model_(std::move(model)) {}

sim::Scenario DesignEvaluator::scenario(const ChamberProfile& profile) const {
  sim::Scenario s = base_;
  s.start_c = profile.start_c;
  s.segments = profile.segments;
  return s;
}

std::string refusal_text(const Precision& p) {
  switch (p.refusal) {
    case Refusal::none: return {};
    case Refusal::too_short:
      return fmt::format("a test of {:.0f} s has fewer than {} windows", p.duration_s, kFewestWindows);
    case Refusal::too_few_windows: return fmt::format("{} windows for {} unknowns", p.windows, p.se.size() + 1);
    case Refusal::constant_regressor:
      return fmt::format("the regressor of '{}' does not vary on this profile", fmt::join(p.refused_terms, ", "));
    case Refusal::collinear:
      return fmt::format("{} are collinear on this profile (condition number {:.3g}, the fitter refuses above {:.0e})",
                         p.refused_terms.empty() ? std::string("the terms") : fmt::format("{}", fmt::join(p.refused_terms, ", ")),
                         p.condition, fit::LinearProblem::kIllConditioned);
  }
  return {};
}

Precision DesignEvaluator::precision(const ChamberProfile& profile) const {
  return evaluate(profile, nullptr);
}

PrecisionDetail DesignEvaluator::detail(const ChamberProfile& profile) const {
  PrecisionDetail d;
  d.precision = evaluate(profile, &d);
  return d;
}

Precision DesignEvaluator::evaluate(const ChamberProfile& profile, PrecisionDetail* detail) const {
  using N = sim::RigDynamics::Node;
  const std::size_t m_terms = model_.terms.size();
  Precision p;
  p.duration_s = profile.duration_s();
  p.se.assign(m_terms, kInfinity);
  p.log_parameter_se.assign(m_terms, std::nan(""));
  if (p.duration_s < kFewestWindows * fit::AveragingOptions{}.window_s) {
    p.refusal = Refusal::too_short;
    return p;
  }
  const sim::Simulator simulator(scenario(profile), rig_, gyro_);
  const sim::ThermalTrace trace = simulator.run_thermal();

  fit::Measurement m;
  m.file = "the planned profile";
  m.time_s = trace.time_s;
  m.temp_c = trace.node(N::sensor);
  m.temp2_c = trace.node(N::sensor2);
  m.gyro_dph.assign(m.time_s.size(), 0.0);
  fit::PipelineOptions options;
  options.remove_outliers = false;
  const fit::PreparedData data = fit::prepare_data(m, options);
  p.windows = data.series.size();
  if (!data.series.temp_c.empty()) {
    const auto [lo, hi] = std::minmax_element(data.series.temp_c.begin(), data.series.temp_c.end());
    p.sensor_min_c = *lo;
    p.sensor_max_c = *hi;
  }
  if (detail) {
    for (std::size_t k = 0; k < trace.time_s.size(); ++k) {
      detail->time_s.push_back(trace.time_s[k]);
      detail->setpoint_c.push_back(trace.setpoint_c[k]);
      detail->chamber_c.push_back(trace.node(N::chamber)[k]);
      detail->sensor_c.push_back(trace.node(N::sensor)[k]);
    }
    detail->window_time_s = data.series.time_s;
  }

  // The design, augmented for each nonlinear parameter with a prior coefficient.
  Eigen::MatrixXd X = fit::design_matrix(data.derived, model_.terms, model_.parameters);
  std::vector<std::size_t> augmented_for;  // the term of each column beyond the model's
  for (std::size_t j = 0; j < m_terms; ++j) {
    const double theta = model_.parameters[j];
    const auto& spec = model_.terms[j]->parameter;
    // As the fitter linearises (fit/pipeline.cpp): a smooth parameter off its bounds.
    if (!spec || !spec->differentiable || !std::isfinite(theta) || model_.prior[j] == 0.0 ||
        !(theta > spec->lower * 1.001 && theta < spec->upper / 1.001))
      continue;
    augmented_for.push_back(j);
    std::vector<double> up(p.windows), down(p.windows);
    model_.terms[j]->compute(data.derived, theta * std::exp(kLogStep), up);
    model_.terms[j]->compute(data.derived, theta * std::exp(-kLogStep), down);
    X.conservativeResize(Eigen::NoChange, X.cols() + 1);
    for (std::size_t i = 0; i < p.windows; ++i)
      X(static_cast<Eigen::Index>(i), X.cols() - 1) = model_.prior[j] * (up[i] - down[i]) / (2.0 * kLogStep);
  }
  const Eigen::Index l = X.rows();
  Eigen::Index cols = X.cols();
  if (l < static_cast<Eigen::Index>(m_terms) + 2) {
    p.refusal = Refusal::too_few_windows;
    return p;
  }
  if (l < cols + 2) {  // too few windows for the parameters too: they stay unknown
    for (std::size_t a : augmented_for) p.log_parameter_se[a] = kInfinity;
    X.conservativeResize(Eigen::NoChange, static_cast<Eigen::Index>(m_terms));
    cols = X.cols();
    augmented_for.clear();
  }
  // Centred and scaled to unit norm: Z = X̃ D⁻¹.
  Eigen::MatrixXd Z = X.rowwise() - X.colwise().mean();
  Eigen::VectorXd norm = Z.colwise().norm().transpose();
  const auto model_cols = static_cast<Eigen::Index>(m_terms);
  for (Eigen::Index j = 0; j < cols; ++j) {
    if (!(norm[j] > 1e-12 * std::max(1.0, X.col(j).cwiseAbs().maxCoeff()))) {
      if (j >= model_cols) {  // a parameter this profile does not move: unknown
        norm[j] = 1.0;
        Z.col(j).setZero();
        continue;
      }
      p.refusal = Refusal::constant_regressor;
      p.refused_terms = {std::string(model_.terms[j]->name)};
      return p;
    }
    Z.col(j) /= norm[j];
  }
  Eigen::MatrixXd gram = Z.transpose() * Z;
  // The fitter refuses on the model's own terms (fit::LinearProblem); a
  // parameter's column that cannot be told from them (or is 0) leaves the
  // parameter unknown (its se +∞) and the coefficients as without it.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram.topLeftCorner(model_cols, model_cols));
  const double lo = eig.eigenvalues().minCoeff(), hi = eig.eigenvalues().maxCoeff();
  p.condition = lo > 0.0 ? hi / lo : kInfinity;
  if (!(p.condition <= fit::LinearProblem::kIllConditioned)) {
    const Eigen::VectorXd v = eig.eigenvectors().col(0);
    for (std::size_t j = 0; j < m_terms; ++j)
      if (std::abs(v[static_cast<Eigen::Index>(j)]) > 0.1) p.refused_terms.emplace_back(model_.terms[j]->name);
    p.refusal = Refusal::collinear;
    return p;
  }
  if (cols > model_cols) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> all(gram);
    if (!(all.eigenvalues().minCoeff() > all.eigenvalues().maxCoeff() / fit::LinearProblem::kIllConditioned)) {
      for (std::size_t a : augmented_for) p.log_parameter_se[a] = kInfinity;
      Z.conservativeResize(Eigen::NoChange, model_cols);
      gram = gram.topLeftCorner(model_cols, model_cols).eval();
      cols = model_cols;
      augmented_for.clear();
    }
  }
  // C·Z: the coloured components in closed form, the white one by window.
  const fit::WindowGrid grid = fit::window_grid(data);
  const fit::NoiseModel& noise = noise_.model;
  Eigen::MatrixXd CZ = Eigen::MatrixXd::Zero(l, cols);
  for (int k : {fit::kFlicker, fit::kGaussMarkov, fit::kRandomWalk})
    if (noise.amplitude[static_cast<std::size_t>(k)] > 0.0)
      CZ += noise.amplitude[static_cast<std::size_t>(k)] * noise.apply(grid, Z, k);
  const double q_w = noise.amplitude[fit::kWhite];
  for (Eigen::Index i = 0; i < l; ++i)
    CZ.row(i) += q_w * noise_.white_factor(data.series.temp_c[static_cast<std::size_t>(i)]) /
                 grid.averaging_s[static_cast<std::size_t>(i)] * Z.row(i);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(gram);
  const Eigen::MatrixXd W = ldlt.solve(Z.transpose());  // cols × l: the estimate's weights (scaled)
  const Eigen::MatrixXd cov = W * CZ * ldlt.solve(Eigen::MatrixXd::Identity(cols, cols));
  for (std::size_t j = 0; j < m_terms; ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    p.se[j] = std::sqrt(std::max(0.0, cov(jj, jj))) / norm[jj];
  }
  for (std::size_t a = 0; a < augmented_for.size(); ++a) {
    const auto c = static_cast<Eigen::Index>(m_terms + a);
    p.log_parameter_se[augmented_for[a]] = std::sqrt(std::max(0.0, cov(c, c))) / norm[c];
  }
  if (detail) {
    for (std::size_t j = 0; j < m_terms; ++j) {
      const Eigen::VectorXd w2 = W.row(static_cast<Eigen::Index>(j)).transpose().array().square();
      const double total = w2.sum();
      std::vector<double> share(static_cast<std::size_t>(l));
      double run = 0.0;
      for (Eigen::Index i = 0; i < l; ++i) share[static_cast<std::size_t>(i)] = (run += w2[i] / total);
      detail->cumulative_share.push_back(std::move(share));
    }
  }
  return p;
}

}  // namespace gyrotherm::studies::plan
