#include "fit/model/noise_model.h"

#include "sim/util/gauss_markov.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>

#include "sim/util/format.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {

namespace {

constexpr double kFloorLog = -30.0;           // log-weight of an absent component
constexpr double kPresentLog = -14.0;         // above this a component is in the model
constexpr double kChi95 = 3.841458820694124;  // χ²₁ 95 % point
// An absent Gauss–Markov process is bounded at 2·kAbsentGaussMarkovHalf − 1
// correlation times log-spaced strictly between Δ and the span (√(Δ·span) the middle one).
constexpr int kAbsentGaussMarkovHalf = 3;
// A Gauss–Markov process (two parameters, τ searched) must lower −2 log L by
// χ²₂'s 95 % point to be added: on white noise it is then claimed rarely.
constexpr double kGaussMarkovGain = 5.991464547107979;

double record_span(const WindowGrid& g) {
  return g.time_s.back() - g.time_s.front() + g.window_s;
}

std::vector<double> flicker_bank(const WindowGrid& g) {
  const double lo = g.window_s, hi = std::max(record_span(g), 2.0 * g.window_s);
  const int count = std::max(2, static_cast<int>(std::ceil(2.0 * std::log10(hi / lo))) + 1);
  std::vector<double> taus;
  for (int i = 0; i < count; ++i)
    taus.push_back(lo * std::pow(hi / lo, static_cast<double>(i) / (count - 1)));
  return taus;
}

// The Allan deviation floor of the bank per unit s: max over τ of √Σ g(τ/τ_i).
double bank_floor(const std::vector<double>& taus, double from_s, double to_s) {
  return std::sqrt(bank_allan_peak(taus, from_s, to_s, 200));
}

// Block means of consecutive windows: [begin, end) of each block.
std::vector<std::pair<Eigen::Index, Eigen::Index>> blocks_of(Eigen::Index n, Eigen::Index most) {
  const Eigen::Index per = std::max<Eigen::Index>(1, (n + most - 1) / most);
  std::vector<std::pair<Eigen::Index, Eigen::Index>> b;
  for (Eigen::Index i = 0; i < n; i += per) b.emplace_back(i, std::min(n, i + per));
  if (b.size() > 1 && 2 * (b.back().second - b.back().first) < per) {
    b[b.size() - 2].second = n;
    b.pop_back();
  }
  return b;
}

Eigen::MatrixXd aggregate(const std::vector<std::pair<Eigen::Index, Eigen::Index>>& blocks,
                          const Eigen::MatrixXd& x) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(blocks.size()), x.cols());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto [i, j] = blocks[b];
    out.row(static_cast<Eigen::Index>(b)) = x.middleRows(i, j - i).colwise().mean();
  }
  return out;
}

// The REML objective over block means: components' unit covariances M_k.
struct Reml {
  Eigen::MatrixXd X;  // block means of [1, design]
  Eigen::VectorXd y;
  std::array<Eigen::MatrixXd, kNoiseKinds> M;  // M[kGaussMarkov] at gm_grid[0]
  std::array<double, kNoiseKinds> norm{};      // mean diagonal of each M (weights are relative to it)
  std::vector<double> gm_log_tau;              // Gauss–Markov on a grid in ln τ, interpolated
  std::vector<Eigen::MatrixXd> gm;

  Eigen::MatrixXd gm_at(double log_tau) const {
    const double pos = std::clamp((log_tau - gm_log_tau.front()) /
                                      (gm_log_tau.back() - gm_log_tau.front()) *
                                      static_cast<double>(gm.size() - 1),
                                  0.0, static_cast<double>(gm.size() - 1));
    const auto k = std::min(static_cast<std::size_t>(pos), gm.size() - 2);
    const double f = pos - static_cast<double>(k);
    return (1.0 - f) * gm[k] + f * gm[k + 1];
  }

  // C = Σ v_k M_k (unnormalised amplitudes) at the block means.
  Eigen::MatrixXd covariance(const std::array<double, kNoiseKinds>& v, double log_tau) const {
    Eigen::MatrixXd C = v[kWhite] * M[kWhite] + v[kFlicker] * M[kFlicker] +
                        v[kRandomWalk] * M[kRandomWalk];
    if (v[kGaussMarkov] > 0.0) C += v[kGaussMarkov] * gm_at(log_tau);
    return C;
  }

  // The REML pieces for C: log|C| + log|XᵀC⁻¹X| and the GLS residual's
  // rᵀC⁻¹r; false where C is not positive definite or the fit is exact.
  bool pieces(const Eigen::MatrixXd& C, double* logdet, double* rss) const {
    const Eigen::LLT<Eigen::MatrixXd> llt(C);
    if (llt.info() != Eigen::Success) return false;
    const Eigen::MatrixXd Xw = llt.matrixL().solve(X);
    const Eigen::VectorXd yw = llt.matrixL().solve(y);
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Xw);
    *rss = (yw - Xw * qr.solve(yw)).squaredNorm();
    *logdet = 0.0;
    for (Eigen::Index i = 0; i < C.rows(); ++i) *logdet += 2.0 * std::log(llt.matrixLLT()(i, i));
    for (Eigen::Index i = 0; i < X.cols(); ++i) *logdet += 2.0 * std::log(std::abs(qr.matrixQR()(i, i)));
    return std::isfinite(*rss) && *rss > 0.0;
  }

  // −2 log L_REML up to a constant for the amplitudes v.
  double minus_two_ll(const std::array<double, kNoiseKinds>& v, double log_tau) const {
    double logdet = 0.0, rss = 0.0;
    if (!pieces(covariance(v, log_tau), &logdet, &rss)) return std::numeric_limits<double>::infinity();
    return logdet + rss;
  }

  // Weights a = (ln w_f, ln w_gm, ln τ, ln w_rw) relative to white; the
  // overall scale profiled out. Returns −2 log L and the scale.
  double profiled(const Eigen::Vector4d& a, double* scale = nullptr) const {
    double logdet = 0.0, rss = 0.0;
    if (!pieces(covariance(amplitudes(a, 1.0), a[2]), &logdet, &rss))
      return std::numeric_limits<double>::infinity();
    const double nu = static_cast<double>(X.rows() - X.cols());
    if (scale) *scale = rss / nu;
    return nu * std::log(rss / nu) + logdet;
  }

  std::array<double, kNoiseKinds> amplitudes(const Eigen::Vector4d& a, double scale) const {
    auto w = [](double l) { return l <= kFloorLog + 1e-9 ? 0.0 : std::exp(l); };
    return {scale / norm[kWhite], scale * w(a[0]) / norm[kFlicker],
            scale * w(a[1]) / norm[kGaussMarkov], scale * w(a[3]) / norm[kRandomWalk]};
  }
};

// Where −2 log L, every amplitude of `m` held but component k's, has risen
// by χ²₁(95 %) from m's as k's amplitude grows (Gauss–Markov at ln τ_c =
// log_tau): the bound of a component the record does not pin down.
double likelihood_bound(const Reml& reml, const NoiseModel& m, int k, double log_tau, double tiny) {
  auto rise = [&](double log_v) {
    std::array<double, kNoiseKinds> v = m.amplitude;
    v[static_cast<std::size_t>(k)] = std::exp(log_v);
    return reml.minus_two_ll(v, log_tau) - m.minus_two_log_likelihood - kChi95;
  };
  double a = std::log(std::max({m.amplitude[static_cast<std::size_t>(k)], tiny, 1e-300}));
  double b = a + 2.0;
  int guard = 0;
  while (rise(b) < 0.0 && guard++ < 40) { a = b; b += 2.0; }
  for (int it = 0; it < 20; ++it) {
    const double c = 0.5 * (a + b);
    (rise(c) < 0.0 ? a : b) = c;
  }
  return std::exp(b);
}

// Nelder–Mead on a box (Lagarias et al., SIAM J. Optim. 9 (1998)), clamped.
Eigen::Vector4d nelder_mead(const std::function<double(const Eigen::Vector4d&)>& f,
                            Eigen::Vector4d start, const Eigen::Vector4d& lo,
                            const Eigen::Vector4d& hi, double step, int max_evals, double* best) {
  auto clamp = [&](Eigen::Vector4d p) { return p.cwiseMax(lo).cwiseMin(hi); };
  std::array<Eigen::Vector4d, 5> s;
  std::array<double, 5> fs;
  s[0] = clamp(start);
  for (int i = 0; i < 4; ++i) {
    s[i + 1] = s[0];
    s[i + 1][i] += (s[0][i] + step <= hi[i]) ? step : -step;
    s[i + 1] = clamp(s[i + 1]);
  }
  int evals = 0;
  for (int i = 0; i < 5; ++i, ++evals) fs[i] = f(s[i]);
  while (evals < max_evals) {
    std::array<int, 5> order = {0, 1, 2, 3, 4};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return fs[a] < fs[b]; });
    const int b = order[0], w = order[4], sw = order[3];
    if (std::abs(fs[w] - fs[b]) < 1e-3) break;  // −2 log L: differences below 1e-3 mean nothing
    Eigen::Vector4d centroid = Eigen::Vector4d::Zero();
    for (int i = 0; i < 4; ++i) centroid += s[order[i]] / 4.0;
    const Eigen::Vector4d xr = clamp(centroid + (centroid - s[w]));
    const double fr = f(xr);
    ++evals;
    if (fr < fs[b]) {
      const Eigen::Vector4d xe = clamp(centroid + 2.0 * (centroid - s[w]));
      const double fe = f(xe);
      ++evals;
      if (fe < fr) { s[w] = xe; fs[w] = fe; } else { s[w] = xr; fs[w] = fr; }
    } else if (fr < fs[sw]) {
      s[w] = xr; fs[w] = fr;
    } else {
      const bool outside = fr < fs[w];
      const Eigen::Vector4d xc = clamp(outside ? centroid + 0.5 * (xr - centroid)
                                               : centroid + 0.5 * (s[w] - centroid));
      const double fc = f(xc);
      ++evals;
      if (fc < (outside ? fr : fs[w])) {
        s[w] = xc; fs[w] = fc;
      } else {
        for (int i = 1; i < 5; ++i) {
          s[order[i]] = clamp(s[b] + 0.5 * (s[order[i]] - s[b]));
          fs[order[i]] = f(s[order[i]]);
          ++evals;
        }
      }
    }
  }
  const int b = static_cast<int>(std::min_element(fs.begin(), fs.end()) - fs.begin());
  *best = fs[b];
  return s[b];
}

}  // namespace

NoiseModel identify_noise(const WindowGrid& grid, const Eigen::MatrixXd& design,
                          const Eigen::VectorXd& y, std::size_t most_blocks) {
  const Eigen::Index n = static_cast<Eigen::Index>(grid.size());
  if (n < design.cols() + 5)
    throw FitError(fmt::format("only {}: too few to identify the noise of a model with {} (need {})",
                                 counted(static_cast<std::size_t>(n), "window"),
                                 counted(static_cast<std::size_t>(design.cols()), "term"), design.cols() + 5));
  NoiseModel model;
  model.flicker_tau_s = flicker_bank(grid);
  model.flicker_floor_per_s = bank_floor(model.flicker_tau_s, grid.window_s, record_span(grid));

  const auto blocks = blocks_of(n, static_cast<Eigen::Index>(std::max<std::size_t>(8, most_blocks)));
  const auto nb = static_cast<Eigen::Index>(blocks.size());
  model.blocks = blocks.size();
  model.block_s = grid.window_s * static_cast<double>(blocks.front().second - blocks.front().first);
  // A·C·Aᵀ by block means, A the block-mean weights: C applied to the
  // columns of Aᵀ (O(l·blocks) time), as many at a time as keep Aᵀ's and
  // C·Aᵀ's columns within kBlockCovBytes (all of them unless the record has
  // some 10⁴ windows: 10⁵ windows' 64 columns would be 100 MB), in two
  // matrices reused pass after pass. Each column is computed alike however
  // many are taken at once.
  constexpr std::size_t kBlockCovBytes = std::size_t{16} << 20;
  const Eigen::Index per_pass = std::clamp<Eigen::Index>(
      static_cast<Eigen::Index>(kBlockCovBytes / (2 * sizeof(double) * static_cast<std::size_t>(n))), 1, nb);
  Eigen::MatrixXd a_t, c_a_t;  // columns first … of Aᵀ, and C times them
  Eigen::Index a_t_first = -1;  // the first column a_t holds (built once when one pass takes all)
  auto block_cov = [&](const NoiseModel& unit, int kind) {
    Eigen::MatrixXd out(nb, nb);
    for (Eigen::Index first = 0; first < nb; first += per_pass) {
      const Eigen::Index count = std::min(per_pass, nb - first);
      if (a_t_first != first || a_t.cols() != count) {
        a_t.setZero(n, count);
        for (Eigen::Index b = first; b < first + count; ++b) {
          const auto [i, j] = blocks[static_cast<std::size_t>(b)];
          a_t.block(i, b - first, j - i, 1).setConstant(1.0 / static_cast<double>(j - i));
        }
        a_t_first = first;
      }
      unit.apply(grid, a_t, c_a_t, kind);
      out.middleCols(first, count) = aggregate(blocks, c_a_t);
    }
    return out;
  };
  Reml reml;
  Eigen::MatrixXd X(n, design.cols() + 1);
  X.col(0).setOnes();
  X.rightCols(design.cols()) = design;
  reml.X = aggregate(blocks, X);
  reml.y = aggregate(blocks, y);
  if (Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(reml.X).rank() < reml.X.cols())
    throw FitError(fmt::format("the model's terms cannot be told apart at the {} block means the "
                                 "noise is identified on", nb));
  for (int k : {kWhite, kFlicker, kRandomWalk}) reml.M[static_cast<std::size_t>(k)] = block_cov(model, k);
  const double lo_tau = std::log(grid.window_s), hi_tau = std::log(record_span(grid));
  for (int k = 0; k < 13; ++k) {
    NoiseModel unit;
    reml.gm_log_tau.push_back(lo_tau + (hi_tau - lo_tau) * k / 12.0);
    unit.gm_tau_s = std::exp(reml.gm_log_tau.back());
    reml.gm.push_back(block_cov(unit, kGaussMarkov));
  }
  for (int k = 0; k < kNoiseKinds; ++k) {
    const Eigen::MatrixXd& m = k == kGaussMarkov ? reml.gm[6] : reml.M[static_cast<std::size_t>(k)];
    reml.norm[static_cast<std::size_t>(k)] = m.diagonal().mean();
  }

  // Stage 1, the standard model (IEEE Std 952): white + flicker + random
  // walk, by Nelder–Mead from several starts, then pruned: a component whose
  // removal costs less than 2 in −2 log L is dropped (Akaike's rule).
  // Stage 2: a Gauss–Markov process is added only if it lowers −2 log L by
  // more than 5.99 (χ²₂ 95 %); what stage 1 kept stays. The order matters:
  // a single Gauss–Markov process can mimic flicker at the windows' time
  // scales and yet have far less power at the long ones the coefficients
  // depend on.
  const Eigen::Vector4d lo(kFloorLog, kFloorLog, lo_tau, kFloorLog), hi(12.0, 12.0, hi_tau, 12.0);
  const double mid = 0.5 * (lo_tau + hi_tau);
  auto f = [&](const Eigen::Vector4d& a) { return reml.profiled(a); };
  Eigen::Vector4d no_gm_hi = hi;
  no_gm_hi[1] = kFloorLog;
  Eigen::Vector4d best_a(kFloorLog, kFloorLog, mid, kFloorLog);
  double best_f = f(best_a);
  std::vector<std::pair<Eigen::Vector4d, double>> tried = {{best_a, best_f}};
  for (const Eigen::Vector4d& start :
       {Eigen::Vector4d(-2, kFloorLog, mid, kFloorLog), Eigen::Vector4d(3, kFloorLog, mid, kFloorLog),
        Eigen::Vector4d(kFloorLog, kFloorLog, mid, -2), Eigen::Vector4d(kFloorLog, kFloorLog, mid, 3),
        Eigen::Vector4d(-2, kFloorLog, mid, -2), Eigen::Vector4d(3, kFloorLog, mid, 3)}) {
    double fv = 0.0;
    const Eigen::Vector4d a = nelder_mead(f, start, lo, no_gm_hi, 3.0, 200, &fv);
    tried.emplace_back(a, fv);
    if (fv < best_f) { best_f = fv; best_a = a; }
  }
  for (;;) {
    int drop = -1;
    double drop_f = INFINITY;
    Eigen::Vector4d drop_a = best_a;
    for (int c : {0, 3}) {
      if (!(best_a[c] > kPresentLog)) continue;
      Eigen::Vector4d start = best_a, hi_c = no_gm_hi;
      start[c] = kFloorLog;
      hi_c[c] = kFloorLog;
      double fv = 0.0;
      const Eigen::Vector4d a = nelder_mead(f, start, lo, hi_c, 1.0, 100, &fv);
      if (fv < drop_f) { drop = c; drop_f = fv; drop_a = a; }
    }
    if (drop < 0 || drop_f - best_f >= 2.0) break;
    best_a = drop_a;
    best_f = drop_f;
  }
  {
    Eigen::Vector4d hi_gm = hi;
    for (int c : {0, 3})
      if (!(best_a[c] > kPresentLog)) hi_gm[c] = kFloorLog;
    double gm_f = INFINITY;
    Eigen::Vector4d gm_a = best_a;
    for (double where : {0.2, 0.5, 0.8}) {
      Eigen::Vector4d start = best_a;
      start[1] = -1.0;
      start[2] = lo_tau + where * (hi_tau - lo_tau);
      double fv = 0.0;
      const Eigen::Vector4d a = nelder_mead(f, start, lo, hi_gm, 2.0, 150, &fv);
      if (fv < gm_f) { gm_f = fv; gm_a = a; }
    }
    if (gm_f < best_f - kGaussMarkovGain && gm_a[1] > kPresentLog) {
      best_a = gm_a;
      best_f = gm_f;
    }
  }
  // The model at a point a, with its uncertainty and bounds.
  const NoiseModel base = model;
  auto finish = [&](const Eigen::Vector4d& point) {
    NoiseModel m = base;
    double scale = 0.0;
    reml.profiled(point, &scale);
    m.amplitude = reml.amplitudes(point, scale);
    m.gm_tau_s = std::exp(point[2]);
    m.present = {true, point[0] > kPresentLog, point[1] > kPresentLog, point[3] > kPresentLog};
    for (int k = 1; k < kNoiseKinds; ++k)
      if (!m.present[static_cast<std::size_t>(k)]) m.amplitude[static_cast<std::size_t>(k)] = 0.0;
    if (!m.present[kGaussMarkov]) m.gm_tau_s = 0.0;
    m.minus_two_log_likelihood = reml.minus_two_ll(m.amplitude, point[2]);

    // Expected information of θ = (v_w, v_f, v_gm, ln τ, v_rw) over the present
    // ones, I_kl = ½ tr(P ∂_kC P ∂_lC) with P the REML projector (Searle, Casella
    // & McCulloch, Variance Components (1992) §6.6); Cov(θ) = I⁻¹.
    std::vector<int> free;
    for (int k = 0; k < kNoiseKinds; ++k)
      if (m.present[static_cast<std::size_t>(k)]) free.push_back(k == kRandomWalk ? 4 : k);
    if (m.present[kGaussMarkov]) free.push_back(3);
    std::sort(free.begin(), free.end());
    {
      const auto& v = m.amplitude;
      const Eigen::LLT<Eigen::MatrixXd> llt(reml.covariance(v, point[2]));
      const Eigen::MatrixXd Ci = llt.solve(Eigen::MatrixXd::Identity(nb, nb));
      const Eigen::MatrixXd CiX = Ci * reml.X;
      const Eigen::MatrixXd P =
          Ci - CiX * (reml.X.transpose() * CiX).ldlt().solve(CiX.transpose());
      auto derivative = [&](int p) -> Eigen::MatrixXd {
        switch (p) {
          case 0: return reml.M[kWhite];
          case 1: return reml.M[kFlicker];
          case 2: return reml.gm_at(point[2]);
          case 3: return v[kGaussMarkov] * (reml.gm_at(point[2] + 0.05) - reml.gm_at(point[2] - 0.05)) / 0.1;
          default: return reml.M[kRandomWalk];
        }
      };
      std::vector<Eigen::MatrixXd> PD;
      for (int p : free) PD.push_back(P * derivative(p));
      const auto nf = static_cast<Eigen::Index>(free.size());
      Eigen::MatrixXd info(nf, nf);
      for (Eigen::Index i = 0; i < nf; ++i)
        for (Eigen::Index j = i; j < nf; ++j)
          info(i, j) = info(j, i) =
              0.5 * (PD[static_cast<std::size_t>(i)].array() * PD[static_cast<std::size_t>(j)].transpose().array()).sum();
      // A direction the record hardly informs gets a large variance (its
      // eigenvalue floored at 1e-12 of the largest), never none.
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(info);
      const double floor = 1e-12 * std::max(eig.eigenvalues().maxCoeff(), 1e-300);
      const Eigen::VectorXd inv = eig.eigenvalues().unaryExpr([&](double e) { return 1.0 / std::max(e, floor); });
      const Eigen::MatrixXd cov = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
      for (Eigen::Index i = 0; i < nf; ++i)
        for (Eigen::Index j = 0; j < nf; ++j)
          m.covariance(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]) = cov(i, j);
    }
    auto log_sd = [&](int k) {
      const int p = k == kRandomWalk ? 4 : k;
      const double value = m.amplitude[static_cast<std::size_t>(k)];
      return value > 0.0 ? std::sqrt(std::max(0.0, m.covariance(p, p))) / value : INFINITY;
    };
    // Identified: present, and known to better than a decade (sd of ln < 1.2).
    for (int k = 0; k < kNoiseKinds; ++k) {
      m.identified[static_cast<std::size_t>(k)] =
          m.present[static_cast<std::size_t>(k)] && log_sd(k) < 1.2;
    }
    // A bound for each component that is not identified: raise its amplitude
    // (the others held) until −2 log L has risen by χ²₁(95 %). An absent
    // Gauss–Markov process has no correlation time of its own: it is bounded
    // at times across the record's scales (the record bounds it differently
    // at each), the one at √(Δ·span) standing for it.
    for (int k = 0; k < kNoiseKinds; ++k) {
      if (m.identified[static_cast<std::size_t>(k)]) continue;
      const double tiny = 1e-12 * m.amplitude[kWhite] * reml.norm[kWhite] / reml.norm[static_cast<std::size_t>(k)];
      if (k == kGaussMarkov && !m.present[kGaussMarkov]) {
        for (int g = 1; g < 2 * kAbsentGaussMarkovHalf; ++g) {
          const double log_tau = lo_tau + (hi_tau - lo_tau) * g / (2 * kAbsentGaussMarkovHalf);
          m.gm_bounds.emplace_back(std::exp(log_tau), likelihood_bound(reml, m, k, log_tau, tiny));
          if (g == kAbsentGaussMarkovHalf) m.upper_bound[kGaussMarkov] = m.gm_bounds.back().second;
        }
        continue;
      }
      m.upper_bound[static_cast<std::size_t>(k)] = likelihood_bound(reml, m, k, point[2], tiny);
    }
    return m;
  };
  model = finish(best_a);
  // Other structures the record supports about as well (Akaike weights
  // within 2 of the best: Burnham & Anderson, Model Selection (2002) §2.6):
  // intervals take the widest of them, since the record cannot tell which
  // one holds. A random walk and a flicker floor, for instance, can fit an
  // 11 h record alike and yet differ tenfold in a trend's variance.
  auto parameter_count = [](const Eigen::Vector4d& a) {
    return 1 + (a[0] > kPresentLog) + 2 * (a[1] > kPresentLog) + (a[3] > kPresentLog);
  };
  auto structure = [](const Eigen::Vector4d& a) {
    return (a[0] > kPresentLog) + 2 * (a[1] > kPresentLog) + 4 * (a[3] > kPresentLog);
  };
  const double best_aic = best_f + 2.0 * parameter_count(best_a);
  std::vector<int> seen = {structure(best_a)};
  std::sort(tried.begin(), tried.end(), [](const auto& p, const auto& q) { return p.second < q.second; });
  for (const auto& [a, fa] : tried) {
    if (std::find(seen.begin(), seen.end(), structure(a)) != seen.end()) continue;
    seen.push_back(structure(a));
    if (fa + 2.0 * parameter_count(a) <= best_aic + 2.0) model.alternatives.push_back(finish(a));
  }
  for (const double v : model.amplitude)
    if (!std::isfinite(v)) throw FitError("the noise amplitudes came out non-finite: nothing to trust");
  return model;
}

}  // namespace gyrotherm::fit
