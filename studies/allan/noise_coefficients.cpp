#include "studies/allan/noise_coefficients.h"
#include "sim/util/numbers.h"

#include <algorithm>
#include <array>
#include <bit>
#include <limits>
#include <cmath>
#include <functional>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>

namespace gyrotherm::studies {
namespace {

// The standard terms as σ² contributions per unit squared coefficient:
// quantisation Q (″), ARW N (°/√h), flicker B (°/h), RRW K (°/h/√h); σ² in (°/h)², τ in s.
constexpr int kTerms = 4;
enum Term { kQ = 0, kN = 1, kB = 2, kK = 3 };
constexpr unsigned kWhiteTerms = (1u << kQ) | (1u << kN);  // white angle and white rate noise
double basis(int term, double tau) {
  switch (term) {
    case kQ: return 3.0 / (tau * tau);
    case kN: return 3600.0 / tau;
    case kB: return kFlickerFloor * kFlickerFloor;
    default: return tau / 10800.0;
  }
}

// "τ = 16–256 s", or "τ = 256 s" when the stretch is a single τ.
std::string tau_span_text(double from_s, double to_s) {
  if (from_s == to_s) return fmt::format("τ = {:.3g} s", from_s);
  return fmt::format("τ = {:.3g}–{:.3g} s", from_s, to_s);
}

constexpr std::size_t kMinClusters = 8;  // rows the bias instability may be read from
constexpr std::size_t kMaxRows = 160;    // rows the weighted fit uses (log-spaced when more)

struct CurveFit {
  std::array<double, kTerms> a{};        // squared coefficients (0: not in the model)
  std::array<double, kTerms> sd{};       // their standard deviations (scaled by the Birge ratio)
  std::array<bool, kTerms> in{};
  double chi2_per_dof = 0.0;
  std::size_t taus = 0;                  // the τ fitted
  bool ok = false;
  // The fitted σ² at τ from the terms in `mask` (all by default).
  double part(double tau, unsigned mask = (1u << kTerms) - 1) const {
    double sum = 0.0;
    for (int k = 0; k < kTerms; ++k)
      if ((mask >> k) & 1u) sum += a[static_cast<std::size_t>(k)] * basis(k, tau);
    return sum;
  }
};

// Generalised least squares of v on the columns `mask` of X with the whitening L (V = LLᵀ).
struct SubFit {
  Eigen::VectorXd a;
  Eigen::MatrixXd cov;
  double chi2 = std::numeric_limits<double>::infinity();  // not fitted
};
SubFit gls(const Eigen::MatrixXd& xw, const Eigen::VectorXd& vw, unsigned mask) {
  std::vector<Eigen::Index> cols;
  for (int k = 0; k < kTerms; ++k)
    if (mask & (1u << k)) cols.push_back(k);
  Eigen::MatrixXd x(xw.rows(), static_cast<Eigen::Index>(cols.size()));
  Eigen::VectorXd scale(x.cols());
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    x.col(j) = xw.col(cols[static_cast<std::size_t>(j)]);
    scale[j] = x.col(j).norm();
    x.col(j) /= scale[j];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(x);
  SubFit f;
  f.a = Eigen::VectorXd::Zero(kTerms);
  f.cov = Eigen::MatrixXd::Zero(kTerms, kTerms);
  if (qr.rank() < x.cols()) return f;
  const Eigen::VectorXd b = qr.solve(vw);
  f.chi2 = (vw - x * b).squaredNorm();
  const Eigen::MatrixXd inv = (x.transpose() * x).inverse();
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    f.a[cols[static_cast<std::size_t>(i)]] = b[i] / scale[i];
    for (Eigen::Index j = 0; j < x.cols(); ++j)
      f.cov(cols[static_cast<std::size_t>(i)], cols[static_cast<std::size_t>(j)]) = inv(i, j) / (scale[i] * scale[j]);
  }
  return f;
}

// `use`: the rows fitted (all if empty); `allowed`: the terms that may enter.
CurveFit fit_curve(const AllanCurve& c, const std::function<bool(const AllanRow&)>& use = {},
                   unsigned allowed = (1u << kTerms) - 1) {
  std::vector<const AllanRow*> rows;
  for (const AllanRow& r : c.rows)
    if (r.adev_dph > 0.0 && r.edf >= 1.0 && (!use || use(r))) rows.push_back(&r);
  if (rows.size() > kMaxRows) {  // log-spaced thinning (τ = all)
    std::vector<const AllanRow*> kept;
    const double lo = std::log(rows.front()->tau_s), hi = std::log(rows.back()->tau_s);
    for (std::size_t k = 0, i = 0; k < kMaxRows; ++k) {
      const double target = lo + (hi - lo) * static_cast<double>(k) / (kMaxRows - 1);
      while (i + 1 < rows.size() && std::log(rows[i]->tau_s) < target) ++i;
      if (kept.empty() || kept.back() != rows[i]) kept.push_back(rows[i]);
    }
    rows = std::move(kept);
  }
  CurveFit out;
  const auto n = static_cast<Eigen::Index>(rows.size());
  if (n < 3) return out;
  Eigen::MatrixXd x(n, kTerms);
  Eigen::VectorXd v(n), model(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const AllanRow& r = *rows[static_cast<std::size_t>(i)];
    v[i] = r.adev_dph * r.adev_dph;
    for (int k = 0; k < kTerms; ++k) x(i, k) = basis(k, r.tau_s);
  }
  model = v;
  SubFit best;
  unsigned best_mask = 0;
  Eigen::MatrixXd xw;
  Eigen::VectorXd vw;
  for (int iteration = 0; iteration < 5; ++iteration) {
    Eigen::VectorXd sd(n);  // of each σ² estimate, at the fitted curve
    for (Eigen::Index i = 0; i < n; ++i)
      sd[i] = std::max(model[i], 0.25 * v[i]) * std::sqrt(2.0 / rows[static_cast<std::size_t>(i)]->edf);
    Eigen::MatrixXd cov(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) {
        const double ti = rows[static_cast<std::size_t>(i)]->tau_s, tj = rows[static_cast<std::size_t>(j)]->tau_s;
        cov(i, j) = std::sqrt(std::min(ti, tj) / std::max(ti, tj)) * sd[i] * sd[j];
      }
    const Eigen::LLT<Eigen::MatrixXd> llt(cov);
    if (llt.info() != Eigen::Success) return out;
    xw = llt.matrixL().solve(x);
    vw = llt.matrixL().solve(v);
    best = SubFit{};
    for (unsigned mask = 1; mask < (1u << kTerms); ++mask) {
      if ((mask & ~allowed) != 0u || static_cast<Eigen::Index>(std::popcount(mask)) >= n) continue;
      SubFit f = gls(xw, vw, mask);
      bool feasible = std::isfinite(f.chi2);
      for (int k = 0; k < kTerms; ++k) feasible = feasible && f.a[k] >= 0.0;
      if (feasible && f.chi2 < best.chi2) {
        best = std::move(f);
        best_mask = mask;
      }
    }
    if (!std::isfinite(best.chi2)) return out;
    model = x * best.a;
  }
  const double dof = static_cast<double>(n - std::popcount(best_mask));
  out.chi2_per_dof = dof > 0.0 ? best.chi2 / dof : 0.0;
  out.taus = rows.size();
  const double birge = std::max(1.0, out.chi2_per_dof);
  // Every term's spread in the full model (the bound of a term left out).
  const SubFit full = gls(xw, vw, allowed);
  for (int k = 0; k < kTerms; ++k) {
    out.in[static_cast<std::size_t>(k)] = (best_mask >> k) & 1u;
    out.a[static_cast<std::size_t>(k)] = best.a[k];
    double var = best.cov(k, k);
    if (!out.in[static_cast<std::size_t>(k)]) {
      // A term left out: its spread with it added to the chosen terms, or in
      // the full model; none when neither can be fitted (NaN: no bound).
      const SubFit with = (allowed >> k) & 1u ? gls(xw, vw, best_mask | (1u << k)) : SubFit{};
      var = std::isfinite(with.chi2) && with.cov.rows() == kTerms ? with.cov(k, k)
            : std::isfinite(full.chi2) && full.cov.rows() == kTerms && ((allowed >> k) & 1u) ? full.cov(k, k)
                                                                                              : std::nan("");
    }
    out.sd[static_cast<std::size_t>(k)] = std::isnan(var) ? var : std::sqrt(std::max(0.0, var) * birge);
  }
  out.ok = true;
  return out;
}

// A fitted term of `f`: shown when its square is above zero at 95 %. Where
// it dominates is judged on `whole`, the curve fitted over every τ with every
// term (f may be a refit of some terms on some τ).
NoiseCoefficient fitted_term(const AllanCurve& c, const CurveFit& f, const CurveFit& whole, int term,
                             CoefficientKind kind) {
  NoiseCoefficient k;
  k.kind = kind;
  if (!f.ok) {
    k.reading = Reading::too_few_taus;
    return k;
  }
  const auto t = static_cast<std::size_t>(term);
  const double a = f.a[t], sd = f.sd[t];
  const double confidence = c.confidence;
  const double z = boost::math::quantile(boost::math::normal(), 0.5 + 0.5 * confidence);
  // Where the term weighs in the curve fitted over every τ.
  double share_best = -1.0;
  for (const AllanRow& r : c.rows) {
    const double total = whole.part(r.tau_s);
    const double share = total > 0.0 ? whole.part(r.tau_s, 1u << term) / total : 0.0;
    if (share >= 0.5) {
      if (k.tau_from_s == 0.0) k.tau_from_s = r.tau_s;
      k.tau_to_s = r.tau_s;
    }
    if (share > share_best) {
      share_best = share;
      k.tau_read_s = r.tau_s;
    }
  }
  if (k.tau_from_s == 0.0) k.tau_from_s = k.tau_to_s = k.tau_read_s;
  k.fit_taus = static_cast<int>(f.taus);
  k.fit_chi2_per_dof = f.chi2_per_dof;
  if (std::isnan(sd)) {
    k.reading = Reading::not_separable;
    return k;
  }
  if (!(a - kZ95 * sd > 0.0)) {
    k.reading = Reading::below_bound;
    k.upper_bound = std::sqrt(std::max(0.0, a) + kZ95 * sd);
    return k;
  }
  k.shown = true;
  k.value = std::sqrt(a);
  k.lo = std::sqrt(std::max(0.0, a - z * sd));
  k.hi = std::sqrt(a + z * sd);
  k.reading = Reading::fitted;
  return k;
}


NoiseCoefficient bias_instability(const AllanCurve& c, const CurveFit& f) {
  NoiseCoefficient k;
  k.kind = CoefficientKind::bias_instability;
  k.method = CoefficientMethod::curve_flat;
  // Rows with at least kMinClusters clusters (terms ≥ (clusters − 2)·m).
  std::vector<std::size_t> usable;
  for (std::size_t i = 0; i < c.rows.size(); ++i)
    if (c.rows[i].adev_dph > 0.0 && c.rows[i].terms + 2 * c.rows[i].m >= kMinClusters * c.rows[i].m)
      usable.push_back(i);
  if (usable.size() < 3) {
    k.reading = Reading::too_few_clusters;
    return k;
  }
  // Flat rows: usable, with a τ on either side, local slope within ±0.2.
  std::vector<bool> flat(c.rows.size(), false);
  for (const std::size_t i : usable)
    flat[i] = i > 0 && i + 1 < c.rows.size() && std::abs(loglog_slope(c.rows, i, 1.0)) <= 0.2;
  // The longest stretch of flat rows (ties: the lowest).
  std::size_t from = 0, to = 0, best_len = 0;
  double best_level = 0.0;
  for (std::size_t i = 0; i < c.rows.size();) {
    if (!flat[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    double level = 0.0, weight = 0.0;
    for (; j < c.rows.size() && flat[j]; ++j) {
      level += c.rows[j].edf * c.rows[j].adev_dph * c.rows[j].adev_dph;
      weight += c.rows[j].edf;
    }
    level /= weight;
    if (j - i > best_len || (j - i == best_len && level < best_level)) {
      from = i;
      to = j - 1;
      best_len = j - i;
      best_level = level;
    }
    i = j;
  }
  std::size_t lowest = usable.front();
  for (const std::size_t i : usable)
    if (c.rows[i].adev_dph < c.rows[lowest].adev_dph) lowest = i;
  const AllanRow& low = c.rows[lowest];
  const double bound = low.adev_dph * std::sqrt(chi2_bound(low.edf, 0.025)) / kFlickerFloor;
  if (best_len > 0) {
    const AllanRow& read = c.rows[from];  // the stretch's best-determined τ (the shortest)
    const double level = std::sqrt(best_level);
    const double lo95 = level * level * chi2_bound(read.edf, 0.975);
    if (lo95 > f.part(read.tau_s, kWhiteTerms)) {
      k.shown = true;
      k.tau_read_s = read.tau_s;
      k.tau_from_s = c.rows[from].tau_s;
      k.tau_to_s = c.rows[to].tau_s;
      k.value = level / kFlickerFloor;
      k.lo = level * std::sqrt(chi2_bound(read.edf, 0.5 + 0.5 * c.confidence)) / kFlickerFloor;
      k.hi = level * std::sqrt(chi2_bound(read.edf, 0.5 - 0.5 * c.confidence)) / kFlickerFloor;
      // A plateau: past the flat part the curve falls below it beyond its
      // interval, as a correlated (Gauss–Markov) bias does past its
      // correlation time and a flicker floor does not.
      bool hump = false;
      for (std::size_t i = to + 1; i < c.rows.size(); ++i) hump = hump || c.rows[i].hi_dph < level;
      k.plateau = hump;
      k.reading = Reading::flat_part;
      return k;
    }
  }
  k.upper_bound = bound;
  k.tau_read_s = low.tau_s;
  k.reading = lowest == usable.back() ? Reading::still_falling : Reading::no_flat_part;
  return k;
}

}  // namespace

CoefficientLabels coefficient_labels(const fit::SensorKind& kind) {
  if (kind.is_gyro)
    return {{"angle random walk", "ARW", "°/√h", "arw_dpsh", 1.0},
            {"bias instability", "bias instability", "°/h", "bias_instability_dph", 1.0},
            {"rate random walk", "RRW", "°/h/√h", "rrw_dph_per_sqrt_h", 1.0},
            {"quantisation", "quantisation", "″", "quantization_arcsec", 1.0},
            "°/h"};
  const fit::NoiseName& white = kind.noise[0];
  const fit::NoiseName& walk = kind.noise[3];
  const bool velocity = white.name == "vrw";
  std::string walk_name(walk.name);
  std::replace(walk_name.begin(), walk_name.end(), '_', ' ');
  // N (base unit at τ = 1 h) is √q_w/60: the white noise reported is factor·√q_w = 60·factor·N.
  return {{velocity ? "velocity random walk" : "white noise", velocity ? "VRW" : "white noise",
           fit::shown_unit(white.unit), std::string(white.name), 60.0 * white.factor},
          {"bias instability", "bias instability", std::string(kind.unit), "bias_instability", 1.0},
          {walk_name, walk_name, fit::shown_unit(walk.unit), std::string(walk.name), 1.0},
          {"quantisation", "quantisation", fmt::format("{}·s", kind.unit), "quantization", 1.0},
          std::string(kind.unit)};
}

NoiseCoefficient reported(NoiseCoefficient k, const CoefficientLabel& label) {
  k.value *= label.scale;
  k.lo *= label.scale;
  k.hi *= label.scale;
  k.upper_bound *= label.scale;
  return k;
}

std::string coefficient_note(const NoiseCoefficient& read, const CoefficientLabels& labels) {
  const CoefficientLabel& label = read.kind == CoefficientKind::arw   ? labels.white
                                  : read.kind == CoefficientKind::rrw ? labels.random_walk
                                  : read.kind == CoefficientKind::quantization ? labels.quantization
                                                                               : labels.bias_instability;
  const NoiseCoefficient k = reported(read, label);
  const std::string what = fmt::format("{} ({} slope)", label.name,
                                       read.kind == CoefficientKind::arw   ? "−½"
                                       : read.kind == CoefficientKind::rrw ? "+½"
                                                                           : "−1");
  const std::string& b_unit = labels.bias_instability.unit;
  const std::string fit_text = fmt::format("weighted fit of the standard terms to σ² at {} τ (χ²/dof {:.2g})",
                                           k.fit_taus, k.fit_chi2_per_dof);
  const std::string span = fmt::format("τ = {:.3g}–{:.3g} s", k.tau_from_s, k.tau_to_s);
  std::string note;
  switch (k.reading) {
    case Reading::too_few_taus: note = "not shown: too few τ for the weighted fit"; break;
    case Reading::not_separable:
      note = fmt::format("not resolved: {} cannot be fitted beside the other terms on these τ (no bound)", what);
      break;
    case Reading::below_bound:
      note = fmt::format("not resolved: {} below {:.3g} (95 % bound of the {})", what, k.upper_bound, fit_text);
      break;
    case Reading::fitted:
      note = fmt::format("{}; {} dominates {}", fit_text, what, tau_span_text(k.tau_from_s, k.tau_to_s));
      break;
    case Reading::too_few_clusters: note = "not shown: fewer than 3 τ with 8 clusters"; break;
    case Reading::flat_part:
      note = fmt::format("the flat part of the curve, {} (local slope within ±0.2{}), σ/0.664{}",
                         tau_span_text(k.tau_from_s, k.tau_to_s), k.tau_from_s == k.tau_to_s ? ", at this τ alone" : "",
                         k.plateau ? "; the curve falls past it: a plateau of a correlated (Gauss–Markov) bias" : "");
      break;
    case Reading::still_falling:
      note = fmt::format("a bound only: the curve still falls at its longest usable τ ({:.3g} s), so the flat "
                         "part is beyond the record; B ≤ {:.3g} {} (the flicker floor lies under every point)",
                         k.tau_read_s, k.upper_bound, b_unit);
      break;
    case Reading::no_flat_part:
      note = fmt::format("not shown: no flat part above what the fitted white noise gives; "
                         "B ≤ {:.3g} {} (the curve's lowest point, τ = {:.3g} s)",
                         k.upper_bound, b_unit, k.tau_read_s);
      break;
    case Reading::noise_model:
      note = fmt::format("the series' noise model (REML): its flicker floor, separated from the white noise (slow "
                         "error a compensation leaves counts in it); flicker {} of the Allan variance at {}",
                         k.flicker_dominates ? "makes most" : "weighs most, if not half,", span);
      break;
    case Reading::unexplained_flat:
      note = fmt::format("a bound only: the curve flattens at {}, but {}; the flat part is what "
                         "the fit's model leaves on a compensated series, or noise no model names; B ≤ {:.3g} {}",
                         span,
                         k.has_noise_model ? "the series' noise model finds no flicker or Gauss–Markov process there"
                                           : "the series is too short for a noise model to say what it is",
                         k.upper_bound, b_unit);
      break;
  }
  if (k.gauss_markov_tau_s > 0.0)
    note += fmt::format("; the series' noise model has a Gauss–Markov process of correlation time {:.3g} s",
                        k.gauss_markov_tau_s);
  return note;
}

double chi2_bound(double edf, double p) { return edf / boost::math::quantile(boost::math::chi_squared(edf), p); }

const char* coefficient_method_name(CoefficientMethod m) {
  static constexpr const char* kNames[] = {"curve_fit", "curve_flat", "noise_model"};  // in the enum's order
  return kNames[static_cast<int>(m)];
}

NoiseCoefficients read_noise_coefficients(const AllanCurve& c) {
  NoiseCoefficients k;
  const CurveFit f = fit_curve(c);
  k.fit_chi2_per_dof = f.chi2_per_dof;
  // White noise (ARW, quantisation) again from the τ where the full fit says
  // it makes at least 80 % of σ²: a real flicker floor rolls off below its
  // shortest correlation time, where a flat B term would over-predict and
  // pull N down (26 % on white + flicker comparable at 10–100 s).
  const auto white_dominated = [&](const AllanRow& r) {
    return f.part(r.tau_s, kWhiteTerms) >= 0.8 * f.part(r.tau_s) && f.part(r.tau_s) > 0.0;
  };
  const CurveFit w = f.ok ? fit_curve(c, white_dominated, kWhiteTerms) : CurveFit{};
  const CurveFit& white_fit = w.ok && w.in[kN] ? w : f;
  k.arw_dpsh = fitted_term(c, white_fit, f, kN, CoefficientKind::arw);
  k.rrw_dph_per_sqrt_h = fitted_term(c, f, f, kK, CoefficientKind::rrw);
  k.quantization_arcsec = fitted_term(c, white_fit, f, kQ, CoefficientKind::quantization);
  k.bias_instability_dph = bias_instability(c, f);
  return k;
}

}  // namespace gyrotherm::studies
