// The noise model's covariance of window means (the kernels, applied to a
// matrix in O(l·m)), its parameters in physical units, and the coefficients'
// sandwich: fit/model/noise_model.h. The identification is noise_model.cpp.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <fmt/format.h>

#include "fit/model/noise_model.h"

#include "sim/util/gauss_markov.h"
#include "sim/util/numbers.h"

namespace gyrotherm::fit {

ExpWindow exp_window(double tau, double delta) {
  const double x = delta / tau;
  const double r = tau / delta;
  if (x > 50.0) return {2.0 * r * r * (x - 1.0), 0.0};  // white at the windows
  const double two_sinh = std::exp(x / 2.0) - std::exp(-x / 2.0);
  return {2.0 * r * r * (x + std::expm1(-x)), r * r * two_sinh * two_sinh};
}

namespace {

// y = C x for the unit exponential kernel (semi-separable: two recursions).
void add_exp_kernel(const WindowGrid& g, double tau, double weight, const Eigen::MatrixXd& x,
                    Eigen::MatrixXd& y) {
  const Eigen::Index n = x.rows();
  const ExpWindow w = exp_window(tau, g.window_s);
  y += weight * w.diagonal * x;
  if (w.off == 0.0 || n < 2) return;
  // decay[i] = e^{−(t_{i+1} − t_i)/τ}; the recursions run down each column
  // (contiguous in memory), Σ_{j<i} forward and Σ_{j>i} backward. Most
  // windows are one spacing apart: exp runs again only where the spacing
  // differs from the previous one (exactly: the same number, the same decay).
  std::vector<double> decay(static_cast<std::size_t>(n - 1));
  double last_spacing = std::numeric_limits<double>::quiet_NaN(), last_decay = 0.0;
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const double spacing = g.time_s[static_cast<std::size_t>(i + 1)] - g.time_s[static_cast<std::size_t>(i)];
    if (spacing != last_spacing) {
      last_spacing = spacing;
      last_decay = std::exp(-spacing / tau);
    }
    decay[static_cast<std::size_t>(i)] = last_decay;
  }
  // Each recursion is a chain of dependent multiply-adds; four columns at a
  // time run four chains side by side (a fifth of the noise model's time on a
  // 8760-window record went into one chain at a time).
  const double scale = weight * w.off;
  constexpr Eigen::Index kLanes = 4;
  for (Eigen::Index c0 = 0; c0 < x.cols(); c0 += kLanes) {
    const Eigen::Index lanes = std::min(kLanes, x.cols() - c0);
    std::array<const double*, kLanes> xc{};
    std::array<double*, kLanes> yc{};
    for (Eigen::Index l = 0; l < lanes; ++l) {
      xc[static_cast<std::size_t>(l)] = x.col(c0 + l).data();
      yc[static_cast<std::size_t>(l)] = y.col(c0 + l).data();
    }
    const auto sweep = [&](auto each_lane) {
      if (lanes == kLanes) {
        for (std::size_t l = 0; l < kLanes; ++l) each_lane(l);
      } else {
        for (std::size_t l = 0; l < static_cast<std::size_t>(lanes); ++l) each_lane(l);
      }
    };
    // Rows before a column's first non-zero (after its last) add exactly 0
    // to the forward (backward) sums: they are skipped. The block means'
    // covariance applies the kernel to columns that are zero outside one
    // block each, so this halves the work there.
    Eigen::Index first = n, last = -1;
    for (Eigen::Index l = 0; l < lanes; ++l) {
      const double* column = xc[static_cast<std::size_t>(l)];
      Eigen::Index a = 0, b = n - 1;
      while (a < n && column[a] == 0.0) ++a;
      while (b > a && column[b] == 0.0) --b;
      if (a < n) {
        first = std::min(first, a);
        last = std::max(last, b);
      }
    }
    if (last < 0) continue;  // all zero
    std::array<double, kLanes> f{};
    for (Eigen::Index i = first + 1; i < n; ++i) {
      const double d = decay[static_cast<std::size_t>(i - 1)];
      sweep([&](std::size_t l) {
        f[l] = d * (f[l] + xc[l][i - 1]);
        yc[l][i] += scale * f[l];
      });
    }
    f.fill(0.0);
    for (Eigen::Index i = last - 1; i >= 0; --i) {
      const double d = decay[static_cast<std::size_t>(i)];
      sweep([&](std::size_t l) {
        f[l] = d * (f[l] + xc[l][i + 1]);
        yc[l][i] += scale * f[l];
      });
    }
  }
}

void add_random_walk(const WindowGrid& g, double weight, const Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
  const Eigen::Index n = x.rows();
  const double t0 = g.time_s.front() - g.window_s / 2.0;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const double* xc = x.col(c).data();
    double* yc = y.col(c).data();
    double below = 0.0;        // Σ_{j<i} s_j x_j
    double above = 0.0;        // Σ_{j>i} x_j
    for (Eigen::Index i = 0; i < n; ++i) above += xc[i];
    for (Eigen::Index i = 0; i < n; ++i) {
      const double s = g.time_s[static_cast<std::size_t>(i)] - t0;
      above -= xc[i];
      yc[i] += weight * (below + s * above + (s - g.window_s / 6.0) * xc[i]);
      below += s * xc[i];
    }
  }
}

void add_white(const WindowGrid& g, double weight, const Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
  const Eigen::Map<const Eigen::VectorXd> a(g.averaging_s.data(), static_cast<Eigen::Index>(g.averaging_s.size()));
  y.noalias() += (weight * a.cwiseInverse()).asDiagonal() * x;
}

}  // namespace

Eigen::MatrixXd NoiseModel::apply(const WindowGrid& grid, const Eigen::MatrixXd& x, int kind) const {
  Eigen::MatrixXd y;
  apply(grid, x, y, kind);
  return y;
}

void NoiseModel::apply(const WindowGrid& grid, const Eigen::MatrixXd& x, Eigen::MatrixXd& y, int kind) const {
  y.setZero(x.rows(), x.cols());
  auto weight = [&](int k) { return kind < 0 ? amplitude[static_cast<std::size_t>(k)] : (kind == k ? 1.0 : 0.0); };
  if (weight(kWhite) > 0.0) add_white(grid, weight(kWhite), x, y);
  if (weight(kFlicker) > 0.0)
    for (double tau : flicker_tau_s) add_exp_kernel(grid, tau, weight(kFlicker), x, y);
  if (weight(kGaussMarkov) > 0.0 && gm_tau_s > 0.0) add_exp_kernel(grid, gm_tau_s, weight(kGaussMarkov), x, y);
  if (weight(kRandomWalk) > 0.0) add_random_walk(grid, weight(kRandomWalk), x, y);
}

std::vector<NoiseModel> plausible_models(const NoiseModel& model, const WindowGrid& grid) {
  std::vector<NoiseModel> out = {model};
  for (const NoiseModel& a : model.alternatives) out.push_back(a);
  const double span = grid.time_s.empty() ? grid.window_s : grid.time_s.back() - grid.time_s.front() + grid.window_s;
  constexpr double z = kZ95;
  // The model with component k at `amplitude` (a Gauss–Markov process at τ_c = tau_s).
  const auto raise = [&](int k, double amplitude, double tau_s) {
    NoiseModel raised = model;
    raised.alternatives.clear();
    raised.amplitude[static_cast<std::size_t>(k)] = amplitude;
    raised.present[static_cast<std::size_t>(k)] = true;
    if (k == kGaussMarkov) raised.gm_tau_s = tau_s;
    out.push_back(std::move(raised));
  };
  for (const int k : {kFlicker, kGaussMarkov, kRandomWalk}) {
    const auto kk = static_cast<std::size_t>(k);
    if (k == kGaussMarkov && !model.present[kGaussMarkov] && !model.gm_bounds.empty()) {
      for (const auto& [tau, bound] : model.gm_bounds) raise(k, bound, tau);
      continue;
    }
    const int p = k == kRandomWalk ? 4 : k;
    const double value = model.amplitude[kk];
    const double upper = model.identified[kk] ? value * std::exp(z * std::sqrt(std::max(0.0, model.covariance(p, p))) / value)
                                              : std::max(model.upper_bound[kk], value);
    if (!(upper > value) || (k == kFlicker && model.flicker_tau_s.empty())) continue;
    raise(k, upper, model.gm_tau_s > 0.0 ? model.gm_tau_s : std::sqrt(grid.window_s * span));
  }
  return out;
}

std::vector<NoiseParameter> NoiseModel::parameters() const {
  std::vector<NoiseParameter> out;
  const double z = kZ95;
  // value = factor · amplitude^½ under the sensor's name and unit, an
  // interval from the log-amplitude's sd.
  constexpr double power = 0.5;
  const std::array<NoiseName, 4>& names = (sensor != nullptr ? *sensor : sensor_kind("")).noise;
  auto add = [&](int k, int p, double factor) {
    NoiseParameter q;
    q.name = std::string(names[static_cast<std::size_t>(k)].name);
    q.unit = std::string(names[static_cast<std::size_t>(k)].unit);
    const double v = amplitude[static_cast<std::size_t>(k)];
    q.value = v > 0.0 ? factor * std::pow(v, power) : 0.0;
    q.identified = identified[static_cast<std::size_t>(k)];
    if (q.identified) {
      const double sd = std::sqrt(std::max(0.0, covariance(p, p))) / v * power;
      q.lower = q.value * std::exp(-z * sd);
      q.upper = q.value * std::exp(z * sd);
    } else {
      q.lower = 0.0;
      q.upper = factor * std::pow(std::max(upper_bound[static_cast<std::size_t>(k)], v), power);
    }
    out.push_back(q);
  };
  add(kWhite, 0, names[kWhite].factor);
  add(kFlicker, 1, flicker_floor_per_s);
  add(kGaussMarkov, 2, 1.0);
  if (present[kGaussMarkov]) {
    NoiseParameter q{"gauss_markov_tau", "s", gm_tau_s, 0, 0, identified[kGaussMarkov]};
    const double sd = std::sqrt(std::max(0.0, covariance(3, 3)));
    q.lower = gm_tau_s * std::exp(-z * sd);
    q.upper = gm_tau_s * std::exp(z * sd);
    out.push_back(q);
  }
  add(kRandomWalk, 4, names[kRandomWalk].factor);
  return out;
}

Eigen::VectorXd NoiseModel::draw(const WindowGrid& g, const std::function<double()>& normal) const {
  const auto n = static_cast<Eigen::Index>(g.size());
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    y[i] = std::sqrt(amplitude[kWhite] / g.averaging_s[static_cast<std::size_t>(i)]) * normal();
  const auto add_exp = [&](double tau, double variance) {
    if (!(variance > 0.0) || !(tau > 0.0) || n == 0) return;
    // The unit-variance process u is simulated exactly: over a window of
    // length Δ (x = Δ/τ), given u at its start, u at its end and the
    // window's mean are jointly normal with means (e^{−x}u₀, u₀(1 − e^{−x})/x),
    // variances 1 − e^{−2x} and Var(mean) − ((1 − e^{−x})/x)², covariance
    // (1 − e^{−x})²/x; between windows u decays by e^{−gap/τ}.
    const double x = g.window_s / tau, ex = std::exp(-x);
    const ExpWindow w = exp_window(tau, g.window_s);
    const double m1 = x > 1e-12 ? -std::expm1(-x) / x : 1.0;
    const double a = -std::expm1(-2.0 * x), c = x > 1e-12 ? std::expm1(-x) * std::expm1(-x) / x : 0.0;
    const double b = std::max(0.0, w.diagonal - m1 * m1);
    const double l11 = std::sqrt(std::max(0.0, a)), l21 = l11 > 0.0 ? c / l11 : 0.0;
    const double l22 = std::sqrt(std::max(0.0, b - l21 * l21));
    const double scale = std::sqrt(variance);
    double u = normal();  // at the first window's start
    for (Eigen::Index i = 0; i < n; ++i) {
      const double z1 = normal(), z2 = normal();
      y[i] += scale * (m1 * u + l21 * z1 + l22 * z2);
      u = ex * u + l11 * z1;  // at the window's end
      if (i + 1 < n) {
        const double gap = std::max(0.0, g.time_s[static_cast<std::size_t>(i + 1)] -
                                             g.time_s[static_cast<std::size_t>(i)] - g.window_s);
        const double d = std::exp(-gap / tau);
        u = d * u + std::sqrt(std::max(0.0, 1.0 - d * d)) * normal();
      }
    }
  };
  for (const double tau : flicker_tau_s) add_exp(tau, amplitude[kFlicker]);
  add_exp(gm_tau_s, amplitude[kGaussMarkov]);
  if (amplitude[kRandomWalk] > 0.0 && n > 0) {
    double level = 0.0, last = g.time_s.front() - g.window_s / 2.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = g.time_s[static_cast<std::size_t>(i)];
      level += std::sqrt(amplitude[kRandomWalk] * std::max(0.0, t - last)) * normal();
      last = t;
      y[i] += level;
    }
  }
  return y;
}

double NoiseModel::allan_variance(double tau_s) const {
  double avar = amplitude[kWhite] / tau_s + amplitude[kRandomWalk] * tau_s / 3.0;
  for (const double t : flicker_tau_s) avar += amplitude[kFlicker] * gauss_markov_allan_shape(tau_s / t);
  if (gm_tau_s > 0.0) avar += amplitude[kGaussMarkov] * gauss_markov_allan_shape(tau_s / gm_tau_s);
  return avar;
}


std::string NoiseModel::description(std::string_view skip) const {
  std::string out = alternatives.empty() ? std::string() : "best of several the record supports alike: ";
  for (const NoiseParameter& p : parameters()) {
    if (p.name == skip) continue;
    if (!out.empty() && out.back() != ' ') out += "; ";
    if (p.name == "gauss_markov_tau") {
      out += fmt::format("tau {:.3g} s [{:.3g}, {:.3g}]", p.value, p.lower, p.upper);
    } else if (p.identified) {
      out += fmt::format("{} {:.3g} [{:.3g}, {:.3g}] {}", p.name, p.value, p.lower, p.upper, shown_unit(p.unit));
    } else {
      out += fmt::format("{} < {:.3g} {} (not pinned down)", p.name, p.upper, shown_unit(p.unit));
    }
  }
  return out;
}

SandwichParts::SandwichParts(const NoiseModel& model, const WindowGrid& grid, const Eigen::MatrixXd& centred) {
  const Eigen::Index l = centred.rows(), m = centred.cols();
  const Eigen::MatrixXd G_inv =
      (centred.transpose() * centred).ldlt().solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::MatrixXd P = centred * G_inv;  // β̂ = Pᵀ y
  // Each component's part of Cov(β̂) per unit amplitude, and Gauss–Markov's change with ln τ.
  covariance = Eigen::MatrixXd::Zero(m, m);
  for (int k = 0; k < kNoiseKinds; ++k) {
    const double v = model.amplitude[static_cast<std::size_t>(k)];
    amplitude[static_cast<std::size_t>(k)] = v;
    unit_part[static_cast<std::size_t>(k)] =
        v > 0.0 ? Eigen::MatrixXd(P.transpose() * model.apply(grid, P, k)) : Eigen::MatrixXd::Zero(m, m);
    covariance += v * unit_part[static_cast<std::size_t>(k)];
  }
  d_tau = Eigen::MatrixXd::Zero(m, m);
  if (model.amplitude[kGaussMarkov] > 0.0) {
    NoiseModel up = model, down = model;
    up.gm_tau_s *= std::exp(0.05);
    down.gm_tau_s *= std::exp(-0.05);
    d_tau = model.amplitude[kGaussMarkov] *
            P.transpose() * (up.apply(grid, P, kGaussMarkov) - down.apply(grid, P, kGaussMarkov)) / 0.1;
  }
  amplitude_covariance = model.covariance;
  max_dof = static_cast<double>(std::max<Eigen::Index>(1, l - m - 1));
}

double SandwichParts::variance(const Eigen::VectorXd& w) const { return w.dot(covariance * w); }

double SandwichParts::dof(const Eigen::VectorXd& w) const {
  // ∂Var/∂θ: per unit amplitude, and per unit of ln τ.
  Eigen::Matrix<double, 5, 1> grad;
  const auto unit = [&](int k) {
    return amplitude[static_cast<std::size_t>(k)] > 0.0 ? w.dot(unit_part[static_cast<std::size_t>(k)] * w) : 0.0;
  };
  grad << unit(kWhite), unit(kFlicker), unit(kGaussMarkov), w.dot(d_tau * w), unit(kRandomWalk);
  const double var = grad.transpose() * amplitude_covariance * grad;
  const double v = variance(w);
  const double dof = var > 0.0 ? 2.0 * v * v / var : max_dof;
  return std::isfinite(dof) ? std::clamp(dof, 1.0, max_dof) : 1.0;  // unknown: the widest
}

std::vector<SandwichParts> sandwich_parts(const NoiseModel& model, const WindowGrid& grid,
                                          const Eigen::MatrixXd& centred) {
  std::vector<SandwichParts> out{SandwichParts(model, grid, centred)};
  for (const NoiseModel& alternative : model.alternatives) out.emplace_back(alternative, grid, centred);
  return out;
}

NoiseSandwich noise_sandwich(const NoiseModel& model, const WindowGrid& grid,
                             const Eigen::MatrixXd& centred) {
  // Each coefficient takes the widest variance among the plausible models
  // (with that model's dof): the record cannot tell which one holds, and an
  // interval too narrow misleads where one too wide only costs precision.
  // The matrix is rescaled to those diagonals.
  const std::vector<SandwichParts> parts = sandwich_parts(model, grid, centred);
  const Eigen::Index m = centred.cols();
  NoiseSandwich out{parts.front().covariance, {}};
  Eigen::VectorXd widest = out.covariance.diagonal();
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(m, j);
    std::size_t chosen = 0;
    for (std::size_t a = 1; a < parts.size(); ++a)
      if (parts[a].covariance(j, j) > widest[j]) {
        widest[j] = parts[a].covariance(j, j);
        chosen = a;
      }
    out.dof.push_back(parts[chosen].dof(e));
  }
  if (parts.size() == 1) return out;  // one model: its covariance as it is
  const Eigen::VectorXd d =
      (widest.array().max(0.0) / out.covariance.diagonal().array().max(1e-300)).sqrt().matrix();
  out.covariance = d.asDiagonal() * out.covariance * d.asDiagonal();
  return out;
}

}  // namespace gyrotherm::fit
