#include "fit/model/noise_bootstrap.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <vector>

#include "sim/util/random.h"

namespace gyrotherm::fit {

namespace {

// The index of component k in θ = (q_w, s², σ², ln τ_c, q_r).
int theta_index(int k) { return k == kRandomWalk ? 4 : k; }

}  // namespace

NoiseModel plausible_noise(const NoiseModel& model, const WindowGrid& grid,
                           const std::function<double()>& normal) {
  NoiseModel m = model;
  m.alternatives.clear();
  // The amplitudes, log-normal with the REML covariance carried to the logs:
  // jointly for the identified components (their logs are known to better
  // than a decade, so the matrix is well scaled), one by one for the others
  // (an estimate near 0 with a huge relative spread), capped at their bound.
  auto theta_of = [&](int p) -> double& {
    return p == 3 ? m.gm_tau_s : m.amplitude[static_cast<std::size_t>(p == 4 ? kRandomWalk : p)];
  };
  auto kind_of = [](int p) { return p == 3 ? kGaussMarkov : p == 4 ? kRandomWalk : p; };
  auto log_variance = [&](int p, int q) {
    const double scale_p = p == 3 ? 1.0 : theta_of(p), scale_q = q == 3 ? 1.0 : theta_of(q);
    return m.covariance(p, q) / (scale_p * scale_q);
  };
  std::vector<int> joint, alone;  // θ indices of the present components
  for (int k = 0; k < kNoiseKinds; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (!m.present[kk] || !(m.amplitude[kk] > 0.0)) continue;
    (m.identified[kk] ? joint : alone).push_back(theta_index(k));
  }
  if (m.present[kGaussMarkov] && m.gm_tau_s > 0.0)
    (m.identified[kGaussMarkov] ? joint : alone).push_back(3);
  std::vector<double> shift(5, 0.0);
  if (!joint.empty()) {
    const auto n = static_cast<Eigen::Index>(joint.size());
    Eigen::MatrixXd log_cov(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j)
        log_cov(i, j) = log_variance(joint[static_cast<std::size_t>(i)], joint[static_cast<std::size_t>(j)]);
    // A symmetric square root that tolerates a semi-definite covariance.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(log_cov);
    const Eigen::MatrixXd root = eig.eigenvectors() *
                                 eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() *
                                 eig.eigenvectors().transpose();
    Eigen::VectorXd z(n);
    for (Eigen::Index i = 0; i < n; ++i) z[i] = normal();
    const Eigen::VectorXd s = root * z;
    for (Eigen::Index i = 0; i < n; ++i) shift[static_cast<std::size_t>(joint[static_cast<std::size_t>(i)])] = s[i];
  }
  for (int p : alone) shift[static_cast<std::size_t>(p)] = std::sqrt(std::max(0.0, log_variance(p, p))) * normal();
  const double span = grid.size() > 0 ? grid.time_s.back() - grid.time_s.front() + grid.window_s : 0.0;
  for (const std::vector<int>* group : {&joint, &alone}) {
    for (int p : *group) {
      double& value = theta_of(p);
      const double estimate = value;
      value *= std::exp(std::clamp(shift[static_cast<std::size_t>(p)], -50.0, 50.0));
      if (p == 3) {
        value = std::clamp(value, grid.window_s, std::max(grid.window_s, span));
        continue;
      }
      const auto k = static_cast<std::size_t>(kind_of(p));
      if (!m.identified[k] && m.upper_bound[k] > 0.0) value = std::min(value, std::max(estimate, m.upper_bound[k]));
      if (!std::isfinite(value)) value = estimate;
    }
  }
  return m;
}

NoiseBootstrap noise_bootstrap(const NoiseModel& model, const WindowGrid& grid,
                               const Eigen::MatrixXd& centred, int draws, std::uint64_t seed) {
  const Eigen::Index l = centred.rows(), m = centred.cols();
  // (X̃ᵀX̃)⁻¹X̃ᵀ once; each draw is then a product.
  const Eigen::MatrixXd solve =
      (centred.transpose() * centred).ldlt().solve(centred.transpose());
  Rng rng = make_rng(seed, streams::fit_bootstrap);
  boost::random::normal_distribution<double> gauss(0.0, 1.0);
  const std::function<double()> normal = [&] { return gauss(rng); };
  std::vector<const NoiseModel*> structures = {&model};
  for (const NoiseModel& a : model.alternatives) structures.push_back(&a);
  NoiseBootstrap out;
  constexpr int kBatch = 64;
  Eigen::MatrixXd batch(l, kBatch);
  for (const NoiseModel* structure : structures) {
    Eigen::MatrixXd& errors = out.errors.emplace_back(draws, m);
    for (int start = 0; start < draws; start += kBatch) {
      const int count = std::min(kBatch, draws - start);
      for (int b = 0; b < count; ++b) batch.col(b) = plausible_noise(*structure, grid, normal).draw(grid, normal);
      errors.middleRows(start, count) = (solve * batch.leftCols(count)).transpose();
    }
  }
  return out;
}

bool bootstrap_by_default(const NoiseModel& model, const WindowGrid& grid, const Eigen::MatrixXd& centred) {
  if (grid.size() < kShortRecordWindows) return true;
  const Eigen::MatrixXd solve = (centred.transpose() * centred).ldlt().solve(centred.transpose());
  auto walk_dominates = [&](const NoiseModel& m) {
    if (!(m.amplitude[kRandomWalk] > 0.0)) return false;
    const Eigen::VectorXd all = (solve * m.apply(grid, solve.transpose())).diagonal();
    const Eigen::VectorXd walk =
        m.amplitude[kRandomWalk] * (solve * m.apply(grid, solve.transpose(), kRandomWalk)).diagonal();
    return (walk.array() > 0.5 * all.array()).any();
  };
  if (walk_dominates(model)) return true;
  return std::any_of(model.alternatives.begin(), model.alternatives.end(), walk_dominates);
}

namespace {

// The q-quantile of v (sorted in place), by linear interpolation.
double quantile(std::vector<double>& v, double q) {
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(at));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

std::pair<double, double> NoiseBootstrap::interval(Eigen::Index j, double estimate, double level) const {
  const double tail = 0.5 * (1.0 - level);
  std::pair<double, double> widest{estimate, estimate};
  for (const Eigen::MatrixXd& e : errors) {
    std::vector<double> d(e.col(j).data(), e.col(j).data() + e.rows());
    const std::pair<double, double> one{estimate - quantile(d, 1.0 - tail), estimate - quantile(d, tail)};
    if (one.second - one.first > widest.second - widest.first) widest = one;
  }
  return widest;
}

double NoiseBootstrap::p_value(Eigen::Index j, double estimate) const {
  double p = 0.0;
  for (const Eigen::MatrixXd& e : errors) {
    const auto beyond = (e.col(j).array().abs() >= std::abs(estimate)).count();
    p = std::max(p, (1.0 + static_cast<double>(beyond)) / (1.0 + static_cast<double>(e.rows())));
  }
  return p;
}

}  // namespace gyrotherm::fit
