#include "studies/diagnose/steps.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace gyrotherm::fit {
namespace {

constexpr std::size_t kMinSide = 4;  // windows on each side of a step

// The OLS-CUSUM statistic of a zero-mean residual.
double cusum(const Eigen::VectorXd& e) {
  const auto n = static_cast<double>(e.size());
  const double var = e.squaredNorm();
  if (var <= 0.0) return 0.0;
  const double lag = e.head(e.size() - 1).dot(e.tail(e.size() - 1));
  const double rho = std::clamp(lag / var, -0.5, 0.9);
  const double long_run = var / n * (1.0 + rho) / (1.0 - rho);
  double s = 0.0, worst = 0.0;
  for (Eigen::Index p = 0; p + 1 < e.size(); ++p) {
    s += e[p];
    worst = std::max(worst, std::abs(s));
  }
  return worst / std::sqrt(long_run * n);
}

}  // namespace

double kolmogorov_p(double x) {
  if (x <= 0.0) return 1.0;
  double p = 0.0;
  for (int m = 1; m <= 100; ++m) {
    const double term = std::exp(-2.0 * m * m * x * x);
    p += (m % 2 == 1 ? 2.0 : -2.0) * term;
    if (term < 1e-16) break;
  }
  return std::clamp(p, 0.0, 1.0);
}

double placebo_step_sd(const Eigen::MatrixXd& design, const Eigen::VectorXd& y, std::size_t step_index) {
  const Eigen::Index l = y.size();
  Eigen::MatrixXd a(l, design.cols() + 1);
  a.col(0).setOnes();
  a.rightCols(design.cols()) = design;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    if (const double norm = a.col(j).norm(); norm > 0.0) a.col(j) /= norm;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(l, a.cols());
  const Eigen::VectorXd e = y - q * (q.transpose() * y);
  constexpr Eigen::Index kAway = 10;
  double sum = 0.0;
  std::size_t n = 0;
  Eigen::VectorXd u(l);
  for (Eigen::Index k = static_cast<Eigen::Index>(kMinSide); k + static_cast<Eigen::Index>(kMinSide) <= l; ++k) {
    if (std::abs(k - static_cast<Eigen::Index>(step_index)) < kAway) continue;
    u.setZero();
    u.tail(l - k).setOnes();
    const Eigen::VectorXd ut = u - q * (q.transpose() * u);
    const double norm2 = ut.squaredNorm();
    if (norm2 <= 1e-12 * static_cast<double>(l)) continue;
    const double size = e.dot(ut) / norm2;
    sum += size * size;
    ++n;
  }
  return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

std::vector<StepCandidate> find_steps(const std::vector<double>& time_s, const Eigen::MatrixXd& design,
                                      const Eigen::VectorXd& y, double alpha, std::size_t max_steps) {
  std::vector<StepCandidate> out;
  const Eigen::Index l = y.size();
  if (l < static_cast<Eigen::Index>(2 * kMinSide)) return out;
  // [1, model, steps so far], columns scaled for the QR.
  Eigen::MatrixXd a(l, design.cols() + 1);
  a.col(0).setOnes();
  a.rightCols(design.cols()) = design;
  while (out.size() < max_steps) {
    Eigen::MatrixXd scaled = a;
    for (Eigen::Index j = 0; j < scaled.cols(); ++j) {
      const double norm = scaled.col(j).norm();
      if (norm > 0.0) scaled.col(j) /= norm;
    }
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(scaled);
    const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(l, scaled.cols());
    const Eigen::VectorXd e = y - q * (q.transpose() * y);
    const double p = kolmogorov_p(cusum(e));
    if (p >= alpha) break;
    // Least squares places the step.
    double best_gain = 0.0;
    Eigen::Index best = 0;
    Eigen::VectorXd u(l);
    for (Eigen::Index k = static_cast<Eigen::Index>(kMinSide); k + static_cast<Eigen::Index>(kMinSide) <= l; ++k) {
      u.setZero();
      u.tail(l - k).setOnes();
      const Eigen::VectorXd ut = u - q * (q.transpose() * u);
      const double norm2 = ut.squaredNorm();
      if (norm2 <= 1e-12 * static_cast<double>(l)) continue;
      const double gain = std::pow(e.dot(ut), 2) / norm2;
      if (gain > best_gain) {
        best_gain = gain;
        best = k;
      }
    }
    if (best == 0) break;
    const auto k = static_cast<std::size_t>(best);
    out.push_back({std::round(0.5 * (time_s[k - 1] + time_s[k])), k, p});
    a.conservativeResize(Eigen::NoChange, a.cols() + 1);
    a.col(a.cols() - 1).setZero();
    a.col(a.cols() - 1).tail(l - best).setOnes();
  }
  std::sort(out.begin(), out.end(),
            [](const StepCandidate& x, const StepCandidate& z) { return x.time_s < z.time_s; });
  return out;
}

}  // namespace gyrotherm::fit
