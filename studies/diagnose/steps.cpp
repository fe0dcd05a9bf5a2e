#include "studies/diagnose/steps.h"

#include "sim/util/input_error.h"

#include <algorithm>
#include <functional>
#include <optional>
#include <cmath>

#include <Eigen/Dense>
#include <boost/random/normal_distribution.hpp>
#include <boost/math/tools/minima.hpp>

#include "sim/util/random.h"

namespace gyrotherm::studies {
namespace {

constexpr Eigen::Index kMinSide = 4;  // windows on each side of a step

// An orthonormal basis Q of [1, design] (columns scaled first, for the QR).
Eigen::MatrixXd model_basis(const Eigen::MatrixXd& design) {
  const Eigen::Index l = design.rows();
  Eigen::MatrixXd a(l, design.cols() + 1);
  a.col(0).setOnes();
  a.rightCols(design.cols()) = design;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    if (const double norm = a.col(j).norm(); norm > 0.0) a.col(j) /= norm;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  return qr.householderQ() * Eigen::MatrixXd::Identity(l, a.cols());
}

// For a residual e ⟂ Q: the fitted size and the gain (eᵀũ_k)²/ũ_kᵀũ_k of a
// step at every window k (NaN where there is none). Since e ⟂ Q, eᵀũ_k =
// Σ_{p≥k} e_p, and ũ_kᵀũ_k = (l − k) − ‖Σ_{p≥k} Q_p‖²: tail sums make the
// whole scan O(l·columns).
struct StepScan {
  Eigen::VectorXd size, gain;
};
StepScan scan_steps(const Eigen::VectorXd& e, const Eigen::MatrixXd& q) {
  const Eigen::Index l = e.size();
  StepScan s{Eigen::VectorXd::Constant(l, std::nan("")), Eigen::VectorXd::Constant(l, std::nan(""))};
  double tail_e = 0.0;
  Eigen::RowVectorXd tail_q = Eigen::RowVectorXd::Zero(q.cols());
  for (Eigen::Index k = l - 1; k >= kMinSide; --k) {
    tail_e += e[k];
    tail_q += q.row(k);
    if (k + kMinSide > l) continue;
    const double norm2 = static_cast<double>(l - k) - tail_q.squaredNorm();
    if (norm2 <= 1e-9 * static_cast<double>(l)) continue;
    s.size[k] = tail_e / norm2;
    s.gain[k] = tail_e * tail_e / norm2;
  }
  return s;
}

// The window where a step removes the most residual variance (0 when none
// can be placed).
Eigen::Index best_step(const Eigen::VectorXd& e, const Eigen::MatrixXd& q) {
  const StepScan s = scan_steps(e, q);
  Eigen::Index best = 0;
  double gain = 0.0;
  for (Eigen::Index k = 0; k < s.gain.size(); ++k)
    if (!std::isnan(s.gain[k]) && s.gain[k] > gain) {
      gain = s.gain[k];
      best = k;
    }
  return best;
}

// The local level model y_t = μ_t + ε_t, μ_{t+1} = μ_t + η_t, with
// var η = q·var ε, run as a Kalman filter with var ε = 1 (σ² concentrated
// out), the first observation starting the level.
struct LevelFilter {
  Eigen::VectorXd v, f, k;  // innovations, their variances, gains
  double sigma2 = 0.0;      // σ̂²
  double minus_2_log_l = 0.0;
};
LevelFilter run_level_filter(const Eigen::VectorXd& y, double q) {
  const Eigen::Index l = y.size();
  LevelFilter r{Eigen::VectorXd::Zero(l), Eigen::VectorXd::Ones(l), Eigen::VectorXd::Zero(l)};
  double a = y[0], p = 1.0 + q, sum_log_f = 0.0;
  for (Eigen::Index t = 1; t < l; ++t) {
    r.v[t] = y[t] - a;
    r.f[t] = p + 1.0;
    r.k[t] = p / r.f[t];
    a += r.k[t] * r.v[t];
    p = p / r.f[t] + q;
    r.sigma2 += r.v[t] * r.v[t] / r.f[t];
    sum_log_f += std::log(r.f[t]);
  }
  const double n = static_cast<double>(l - 1);
  r.sigma2 /= n;
  r.minus_2_log_l = n * std::log(std::max(r.sigma2, 1e-300)) + sum_log_f;
  return r;
}

// x less a step before window `at` (joint least squares with the model q);
// x itself when at = 0 (no step).
Eigen::VectorXd without_step(const Eigen::VectorXd& x, const Eigen::MatrixXd& q, Eigen::Index at) {
  if (at == 0) return x;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(x.size());
  u.tail(x.size() - at).setOnes();
  u -= q * (q.transpose() * u);
  u.normalize();
  return x - u * u.dot(x);
}

// The largest |t| of a level shift in e, q fitted to `noise` (e less its best step).
double max_level_shift_t(const Eigen::VectorXd& e, const Eigen::MatrixXd& q, const Eigen::VectorXd& noise) {
  return level_shift_t(e, q, fit_level_q(noise)).cwiseAbs().maxCoeff();
}

// The innovations of x under the gains of a filter already run (the filter is
// linear: its gains depend on q alone), scaled by 1/√F_t: the whitening of x.
Eigen::VectorXd whiten(const Eigen::VectorXd& x, const LevelFilter& filter) {
  Eigen::VectorXd w = Eigen::VectorXd::Zero(x.size());
  double a = x[0];
  for (Eigen::Index t = 1; t < x.size(); ++t) {
    const double v = x[t] - a;
    a += filter.k[t] * v;
    w[t] = v / std::sqrt(filter.f[t]);
  }
  return w;
}

}  // namespace

double fit_level_q(const Eigen::VectorXd& y) {
  const auto best = boost::math::tools::brent_find_minima(
      [&](double log_q) { return run_level_filter(y, std::exp(log_q)).minus_2_log_l; }, std::log(1e-8), std::log(1e2),
      20);
  return std::exp(best.first);
}

// The GLS t-statistic of a level shift before each window k, jointly with
// the columns of `model`, under the local level model with ratio q. The
// shift's whitened regressor is w_k(t) = L_k···L_{t−1}/√F_t (t ≥ k), so
// ỹᵀw_k and ‖w_k‖² follow the smoother's backward recursions
// r_{k−1} = v_k/F_k + L_k r_k and N_{k−1} = 1/F_k + L_k² N_k: without a
// model the statistic is the standardised smoothed level disturbance
// (Harvey & Koopman 1992; de Jong & Penzer 1998 show it is the t-test of
// that intervention), and with one the same recursion carries the
// projections Q̃ᵀw_k. O(l·columns). Entries outside [kMinSide, l − kMinSide]
// are zero.
Eigen::VectorXd level_shift_t(const Eigen::VectorXd& y, const Eigen::MatrixXd& model, double q) {
  const Eigen::Index l = y.size();
  const LevelFilter filter = run_level_filter(y, q);
  const Eigen::VectorXd wy = whiten(y, filter);
  Eigen::MatrixXd wx(l, model.cols());
  for (Eigen::Index j = 0; j < model.cols(); ++j) wx.col(j) = whiten(model.col(j), filter);
  // An orthonormal basis of the whitened model (the intercept whitens to 0).
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(wx);
  qr.setThreshold(1e-9);
  const Eigen::Index rank = qr.rank();
  const Eigen::MatrixXd wq = qr.householderQ() * Eigen::MatrixXd::Identity(l, rank);
  const Eigen::VectorXd c = wq.transpose() * wy;
  const double sigma2 = (wy.squaredNorm() - c.squaredNorm()) / static_cast<double>(l - 1 - rank);
  Eigen::VectorXd stat = Eigen::VectorXd::Zero(l);
  if (!(sigma2 > 0.0)) return stat;
  double r = 0.0, n = 0.0;
  Eigen::RowVectorXd z = Eigen::RowVectorXd::Zero(rank);
  for (Eigen::Index t = l - 1; t >= 1; --t) {
    const double lt = 1.0 - filter.k[t], root_f = std::sqrt(filter.f[t]);
    r = wy[t] / root_f + lt * r;
    n = 1.0 / filter.f[t] + lt * lt * n;
    z = wq.row(t) / root_f + lt * z;
    const double norm2 = n - z.squaredNorm();
    if (t >= kMinSide && t + kMinSide <= l && norm2 > 1e-12 * n) stat[t] = (r - z.dot(c)) / std::sqrt(norm2 * sigma2);
  }
  return stat;
}

double level_shift_statistic(const Eigen::VectorXd& e, const Eigen::MatrixXd& q) {
  return max_level_shift_t(e, q, without_step(e, q, best_step(e, q)));
}

double level_shift_p(const Eigen::VectorXd& noise, const Eigen::MatrixXd& q, double statistic, int replicates,
                     Rng& rng, const fit::NoiseModel* model, const fit::WindowGrid* grid) {
  const Eigen::Index l = noise.size();
  const bool from_model = model != nullptr && grid != nullptr && static_cast<Eigen::Index>(grid->size()) == l;
  const double ratio = from_model ? 0.0 : fit_level_q(noise);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  const std::function<double()> draw_normal = [&] { return normal(rng); };
  int as_large = 0;
  Eigen::VectorXd x(l);
  for (int s = 0; s < replicates; ++s) {
    if (from_model) {
      x = model->draw(*grid, draw_normal);
    } else {
      double level = 0.0;
      for (Eigen::Index t = 0; t < l; ++t) {
        x[t] = level + normal(rng);
        level += std::sqrt(ratio) * normal(rng);
      }
    }
    x -= q * (q.transpose() * x);
    as_large += level_shift_statistic(x, q) >= statistic ? 1 : 0;
  }
  return (1.0 + as_large) / (1.0 + replicates);
}

double placebo_step_sd(const Eigen::MatrixXd& design, const Eigen::VectorXd& y, std::size_t step_index) {
  const Eigen::MatrixXd q = model_basis(design);
  const Eigen::VectorXd e = y - q * (q.transpose() * y);
  const StepScan s = scan_steps(e, q);
  constexpr Eigen::Index kAway = 10;
  double sum = 0.0;
  std::size_t n = 0;
  for (Eigen::Index k = 0; k < s.size.size(); ++k) {
    if (std::isnan(s.size[k]) || std::abs(k - static_cast<Eigen::Index>(step_index)) < kAway) continue;
    sum += s.size[k] * s.size[k];
    ++n;
  }
  return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

std::vector<StepCandidate> find_steps(const std::vector<double>& time_s, const Eigen::MatrixXd& design,
                                      const Eigen::VectorXd& y, const StepSearch& search) {
  std::vector<StepCandidate> out;
  const Eigen::Index l = y.size();
  if (l < 2 * kMinSide) return out;
  Rng rng = make_rng(search.seed, streams::diagnosis_step_bootstrap);
  Eigen::MatrixXd a = design;  // the model and the steps so far
  while (out.size() < search.max_steps) {
    const Eigen::MatrixXd q = model_basis(a);
    const Eigen::VectorXd e = y - q * (q.transpose() * y);
    const Eigen::Index best = best_step(e, q);
    if (best == 0) break;
    // The noise without the step, found once: for the statistic's q and the bootstrap.
    const Eigen::VectorXd noise = without_step(e, q, best);
    // The model with this step: the fixed effects the record's noise is
    // identified with, and, if the step stands, the next search's model.
    Eigen::MatrixXd with(l, a.cols() + 1);
    with.leftCols(a.cols()) = a;
    with.col(a.cols()).setZero();
    with.col(a.cols()).tail(l - best).setOnes();
    std::optional<fit::NoiseModel> model;
    if (search.grid != nullptr && static_cast<Eigen::Index>(search.grid->size()) == l) {
      try {
        model = fit::identify_noise(*search.grid, with, y, 128);  // window-level draws: the finer blocks
      } catch (const InputError&) {
      }
    }
    const double p = level_shift_p(noise, q, max_level_shift_t(e, q, noise), search.replicates, rng,
                                   model ? &*model : nullptr, search.grid);
    if (p >= search.alpha) break;
    const auto k = static_cast<std::size_t>(best);
    out.push_back({std::round(0.5 * (time_s[k - 1] + time_s[k])), k, p});
    a = std::move(with);
  }
  std::sort(out.begin(), out.end(),
            [](const StepCandidate& x, const StepCandidate& z) { return x.time_s < z.time_s; });
  return out;
}

}  // namespace gyrotherm::studies
