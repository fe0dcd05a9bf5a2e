#include "fit/model/noise_whitening.h"

#include <Eigen/Dense>
#include <cmath>
#include <fmt/format.h>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {

NoiseWhitener::NoiseWhitener(const NoiseModel& model, const WindowGrid& grid) {
  const std::size_t l = grid.size();
  time_s_ = grid.time_s;
  const double t0 = l > 0 ? grid.time_s.front() - grid.window_s / 2.0 : 0.0;
  since_s_.resize(l);
  for (std::size_t n = 0; n < l; ++n) since_s_[n] = grid.time_s[n] - t0;

  // The components: their off-diagonal amplitude, rate and diagonal share.
  std::vector<double> a, rate;
  std::vector<bool> walk;
  double kernel_diagonal = 0.0;  // every exponential kernel's window variance, summed
  const auto add_kernel = [&](double tau, double amplitude) {
    if (!(amplitude > 0.0) || !(tau > 0.0)) return;
    const ExpWindow w = exp_window(tau, grid.window_s);
    kernel_diagonal += amplitude * w.diagonal;
    if (w.off == 0.0) return;  // white at the windows: the diagonal alone
    a.push_back(amplitude * w.off);
    rate.push_back(1.0 / tau);
    walk.push_back(false);
  };
  if (model.amplitude[kFlicker] > 0.0)
    for (double tau : model.flicker_tau_s) add_kernel(tau, model.amplitude[kFlicker]);
  if (model.amplitude[kGaussMarkov] > 0.0) add_kernel(model.gm_tau_s, model.amplitude[kGaussMarkov]);
  const double q_r = model.amplitude[kRandomWalk];
  if (q_r > 0.0) {
    a.push_back(q_r);
    rate.push_back(0.0);
    walk.push_back(true);
  }
  const auto r = static_cast<Eigen::Index>(a.size());
  a_ = Eigen::Map<const Eigen::VectorXd>(a.data(), r);
  rate_ = Eigen::Map<const Eigen::VectorXd>(rate.data(), r);
  random_walk_ = walk;

  d_.resize(l);
  w_.resize(r, static_cast<Eigen::Index>(l));
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(r, r);
  Eigen::VectorXd v(r), phi(r);
  for (std::size_t n = 0; n < l; ++n) {
    const auto nn = static_cast<Eigen::Index>(n);
    if (n > 0) {
      const double dt = time_s_[n] - time_s_[n - 1];
      for (Eigen::Index j = 0; j < r; ++j) phi[j] = random_walk_[static_cast<std::size_t>(j)] ? 1.0 : std::exp(-rate_[j] * dt);
      s.noalias() += d_[n - 1] * w_.col(nn - 1) * w_.col(nn - 1).transpose();
      s = phi.asDiagonal() * s * phi.asDiagonal();
    }
    const double averaging = n < grid.averaging_s.size() ? grid.averaging_s[n] : grid.window_s;
    double c_nn = kernel_diagonal;
    if (model.amplitude[kWhite] > 0.0) c_nn += model.amplitude[kWhite] / averaging;
    if (q_r > 0.0) c_nn += q_r * (since_s_[n] - grid.window_s / 6.0);
    for (Eigen::Index j = 0; j < r; ++j) v[j] = random_walk_[static_cast<std::size_t>(j)] ? since_s_[n] : 1.0;
    const Eigen::VectorXd su = s * a_;
    d_[n] = c_nn - a_.dot(su);
    if (!(d_[n] > 0.0) || !std::isfinite(d_[n]))
      throw FitError(fmt::format("the noise model's covariance is not positive definite at window {} of {}", n + 1, l));
    w_.col(nn) = (v - su) / d_[n];
  }
}

Eigen::MatrixXd NoiseWhitener::whiten(const Eigen::MatrixXd& x) const {
  const Eigen::Index l = static_cast<Eigen::Index>(d_.size()), r = a_.size();
  Eigen::MatrixXd z(x.rows(), x.cols());
  // The decays between windows, once for every column.
  Eigen::MatrixXd phi(r, l);
  for (Eigen::Index n = 1; n < l; ++n) {
    const double dt = time_s_[static_cast<std::size_t>(n)] - time_s_[static_cast<std::size_t>(n - 1)];
    for (Eigen::Index j = 0; j < r; ++j)
      phi(j, n) = random_walk_[static_cast<std::size_t>(j)] ? 1.0 : std::exp(-rate_[j] * dt);
  }
  // Every column at once: f (r × columns) runs down the windows.
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(r, x.cols());
  for (Eigen::Index n = 0; n < l; ++n) {
    if (n > 0) {
      f.noalias() += w_.col(n - 1) * z.row(n - 1);
      f = phi.col(n).asDiagonal() * f;
    }
    z.row(n).noalias() = x.row(n) - a_.transpose() * f;
  }
  const Eigen::Map<const Eigen::VectorXd> d(d_.data(), l);
  z = d.cwiseSqrt().cwiseInverse().asDiagonal() * z;
  return z;
}

Eigen::MatrixXd NoiseWhitener::solve(const Eigen::MatrixXd& x) const {
  const Eigen::Index l = static_cast<Eigen::Index>(d_.size()), r = a_.size();
  const Eigen::Map<const Eigen::VectorXd> d(d_.data(), l);
  const Eigen::MatrixXd w = d.cwiseSqrt().cwiseInverse().asDiagonal() * whiten(x);  // D⁻¹L⁻¹x
  Eigen::MatrixXd y(x.rows(), x.cols());
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(r, x.cols());
  for (Eigen::Index m = l - 1; m >= 0; --m) {
    if (m < l - 1) {
      const double dt = time_s_[static_cast<std::size_t>(m + 1)] - time_s_[static_cast<std::size_t>(m)];
      g.noalias() += a_ * y.row(m + 1);
      for (Eigen::Index j = 0; j < r; ++j)
        if (!random_walk_[static_cast<std::size_t>(j)]) g.row(j) *= std::exp(-rate_[j] * dt);
    }
    y.row(m).noalias() = w.row(m) - w_.col(m).transpose() * g;
  }
  return y;
}

Eigen::VectorXd NoiseWhitener::whiten(const Eigen::VectorXd& x) const {
  return whiten(Eigen::MatrixXd(x)).col(0);
}

double NoiseWhitener::log_determinant() const {
  double sum = 0.0;
  for (double d : d_) sum += std::log(d);
  return sum;
}

GlsFit gls(const NoiseWhitener& whitener, const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  const Eigen::Index l = y.size();
  Eigen::MatrixXd design(l, x.cols() + 1);
  design.col(0).setOnes();
  design.rightCols(x.cols()) = x;
  const Eigen::MatrixXd xw = whitener.whiten(design);
  const Eigen::VectorXd yw = whitener.whiten(y);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(xw);
  if (qr.rank() < xw.cols())
    throw FitError(fmt::format("the design's {} columns are linearly dependent under the noise model", xw.cols()));
  GlsFit out;
  out.beta = qr.solve(yw);
  out.whitened_residual = yw - xw * out.beta;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(xw.cols(), xw.cols());
  out.covariance = (xw.transpose() * xw).ldlt().solve(identity);
  out.log_likelihood = -0.5 * (static_cast<double>(l) * std::log(2.0 * M_PI) + whitener.log_determinant() +
                               out.whitened_residual.squaredNorm());
  return out;
}

}  // namespace gyrotherm::fit

namespace gyrotherm::fit {

double widest_variance(const std::vector<NoiseWhitener>& whiteners, const Eigen::MatrixXd& x, Eigen::Index k) {
  Eigen::MatrixXd design(x.rows(), x.cols() + 1);
  design << Eigen::VectorXd::Ones(x.rows()), x;
  double widest = 0.0;
  for (const NoiseWhitener& w : whiteners) {
    const Eigen::MatrixXd xw = w.whiten(design);
    const Eigen::MatrixXd info = xw.transpose() * xw;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(info);
    if (ldlt.info() != Eigen::Success) continue;
    const Eigen::VectorXd unit = Eigen::VectorXd::Unit(info.rows(), k);
    widest = std::max(widest, unit.dot(ldlt.solve(unit)));
  }
  return widest;
}

}  // namespace gyrotherm::fit
