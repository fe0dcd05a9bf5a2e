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
  // The amplitudes, log-normal with the REML covariance carried to the logs.
  std::vector<int> free;  // θ indices of the present components
  for (int k = 0; k < kNoiseKinds; ++k)
    if (m.present[static_cast<std::size_t>(k)] && m.amplitude[static_cast<std::size_t>(k)] > 0.0)
      free.push_back(theta_index(k));
  if (m.present[kGaussMarkov] && m.gm_tau_s > 0.0) free.push_back(3);
  std::sort(free.begin(), free.end());
  const auto nf = static_cast<Eigen::Index>(free.size());
  auto theta = [&](int p) {
    return p == 3 ? 1.0 : m.amplitude[static_cast<std::size_t>(p == 4 ? kRandomWalk : p)];
  };
  Eigen::MatrixXd log_cov(nf, nf);
  for (Eigen::Index i = 0; i < nf; ++i)
    for (Eigen::Index j = 0; j < nf; ++j) {
      const int p = free[static_cast<std::size_t>(i)], q = free[static_cast<std::size_t>(j)];
      log_cov(i, j) = m.covariance(p, q) / (theta(p) * theta(q));
    }
  // A symmetric square root that tolerates a semi-definite covariance.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(log_cov);
  const Eigen::MatrixXd root = eig.eigenvectors() *
                               eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() *
                               eig.eigenvectors().transpose();
  Eigen::VectorXd z(nf);
  for (Eigen::Index i = 0; i < nf; ++i) z[i] = normal();
  const Eigen::VectorXd shift = root * z;
  const double span = grid.size() > 0 ? grid.time_s.back() - grid.time_s.front() + grid.window_s : 0.0;
  for (Eigen::Index i = 0; i < nf; ++i) {
    const int p = free[static_cast<std::size_t>(i)];
    if (p == 3) {
      m.gm_tau_s = std::clamp(m.gm_tau_s * std::exp(shift[i]), grid.window_s, std::max(grid.window_s, span));
      continue;
    }
    const int k = p == 4 ? kRandomWalk : p;
    double& a = m.amplitude[static_cast<std::size_t>(k)];
    a *= std::exp(shift[i]);
    if (!m.identified[static_cast<std::size_t>(k)] && m.upper_bound[static_cast<std::size_t>(k)] > 0.0)
      a = std::min(a, m.upper_bound[static_cast<std::size_t>(k)]);
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
