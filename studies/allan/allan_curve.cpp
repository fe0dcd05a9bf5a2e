#include "studies/allan/allan_curve.h"

#include <algorithm>
#include <cmath>

#include <boost/math/distributions/chi_squared.hpp>
#include <fmt/format.h>

#include "fit/data/median.h"
#include "studies/allan/greenhall_edf.h"
#include "sim/util/input_error.h"
#include "sim/util/format.h"

namespace gyrotherm::studies {
namespace {

// Block averages the lag-1 autocorrelation needs. Riley & Greenhall's 30 lets
// r1 stray by ±0.18, enough to call one white point in six flicker angle
// noise (α = 1) and under-state its interval; with 100 it strays by ±0.1.
constexpr std::size_t kAcfAverages = 100;

// A gap-free run: its rates and its angle x_k = Σ_{i<k} (y_i − ȳ) (in rate ×
// samples; the mean cancels in the second differences and keeps x small),
// summed with Neumaier's compensation so long runs lose no digits.
struct Run {
  std::span<const double> rate;
  std::vector<double> angle;
};

std::vector<double> angle_of(std::span<const double> rate) {
  double mean = 0.0;
  for (const double y : rate) mean += y;
  mean /= static_cast<double>(rate.size());
  std::vector<double> x(rate.size() + 1, 0.0);
  double sum = 0.0, carry = 0.0;
  for (std::size_t i = 0; i < rate.size(); ++i) {
    const double y = rate[i] - mean;
    const double t = sum + y;
    carry += std::abs(sum) >= std::abs(y) ? (sum - t) + y : (y - t) + sum;
    sum = t;
    x[i + 1] = sum + carry;
  }
  return x;
}

// Σ_j (x_{j+2m} − 2x_{j+m} + x_j)² and the number of terms, in (rate × samples)².
std::pair<double, std::size_t> second_differences(const std::vector<double>& x, std::size_t m) {
  const std::size_t n = x.size() - 1;
  if (n < 2 * m) return {0.0, 0};
  double sum = 0.0;
  for (std::size_t j = 0; j + 2 * m <= n; ++j) {
    const double d = x[j + 2 * m] - 2.0 * x[j + m] + x[j];
    sum += d * d;
  }
  return {sum, n - 2 * m + 1};
}

// Riley & Greenhall's lag-1 autocorrelation identification on the runs' m-block
// averages, pooled (products only within a run). Returns false when there are
// fewer than kAcfAverages averages.
bool acf_alpha(const std::vector<Run>& runs, std::size_t m, int& alpha) {
  std::vector<std::vector<double>> z;
  std::size_t count = 0;
  for (const Run& r : runs) {
    std::vector<double> blocks(r.rate.size() / m);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      double s = 0.0;
      for (std::size_t i = 0; i < m; ++i) s += r.rate[b * m + i];
      blocks[b] = s / static_cast<double>(m);
    }
    count += blocks.size();
    if (blocks.size() >= 2) z.push_back(std::move(blocks));
  }
  if (count < kAcfAverages) return false;
  for (int d = 0;; ++d) {
    double mean = 0.0;
    std::size_t n = 0;
    for (const auto& v : z)
      for (const double y : v) {
        mean += y;
        ++n;
      }
    if (n < 3) return false;
    mean /= static_cast<double>(n);
    double num = 0.0, den = 0.0;
    for (const auto& v : z)
      for (std::size_t i = 0; i < v.size(); ++i) {
        den += (v[i] - mean) * (v[i] - mean);
        if (i + 1 < v.size()) num += (v[i] - mean) * (v[i + 1] - mean);
      }
    const double r1 = den > 0.0 ? num / den : 0.0;
    const double delta = r1 / (1.0 + r1);
    if (delta < 0.25 || d >= 2) {
      alpha = std::clamp(static_cast<int>(std::lround(-2.0 * (delta + d))), -2, 2);
      return true;
    }
    for (auto& v : z) {
      for (std::size_t i = 0; i + 1 < v.size(); ++i) v[i] = v[i + 1] - v[i];
      v.pop_back();
    }
  }
}

std::vector<std::size_t> factors(TauSpacing spacing, std::size_t largest) {
  std::vector<std::size_t> m;
  for (std::size_t k = 1; k <= largest;) {
    m.push_back(k);
    k = spacing == TauSpacing::all ? k + 1 : spacing == TauSpacing::octave ? 2 * k : 10 * k;
  }
  return m;
}

}  // namespace

std::string noise_type_name(int alpha) {
  switch (alpha) {
    case 2: return "quantization";
    case 1: return "flicker_angle";
    case 0: return "angle_random_walk";
    case -1: return "bias_instability";
    default: return "rate_random_walk";
  }
}

double loglog_slope(const std::vector<AllanRow>& rows, std::size_t i, double octaves) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, k = 0;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const bool near = std::abs(std::log2(rows[j].tau_s / rows[i].tau_s)) <= octaves + 1e-9 || j + 1 == i || j == i + 1;
    if (near && rows[j].adev_dph > 0.0) {
      const double x = std::log(rows[j].tau_s), y = std::log(rows[j].adev_dph);
      sx += x; sy += y; sxx += x * x; sxy += x * y; k += 1.0;
    }
  }
  const double d = k > 0.0 ? sxx - sx * sx / k : 0.0;
  return k >= 3.0 && d > 0.0 ? (sxy - sx * sy / k) / d : std::nan("");
}

double overlapping_adev(std::span<const double> rate, std::size_t m) {
  const auto [sum, terms] = second_differences(angle_of(rate), m);
  if (terms == 0) return std::nan("");
  const double md = static_cast<double>(m);  // τ in samples: x is in rate × samples
  return std::sqrt(sum / (2.0 * md * md * static_cast<double>(terms)));
}

AllanCurve allan_curve(std::span<const double> time_s, std::span<const double> rate_dph,
                       const AllanOptions& options, std::string name) {
  if (!(options.confidence > 0.0 && options.confidence < 1.0))
    throw InputError(fmt::format("--ci {}: the confidence must be between 0 and 1 (e.g. 0.68 or 0.95)",
                                 options.confidence));
  const std::size_t n = time_s.size();
  if (n != rate_dph.size() || n < 3)
    throw InputError(fmt::format("{}: {}; the Allan deviation needs at least 3", name, counted(n, "sample")));
  std::vector<double> steps(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) steps[i] = time_s[i + 1] - time_s[i];
  AllanCurve c;
  c.name = std::move(name);
  c.tau0_s = fit::median_of(steps);
  c.samples = n;
  c.span_s = time_s[n - 1] - time_s[0];
  c.confidence = options.confidence;
  std::vector<Run> runs;
  std::size_t start = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i + 1 == n || steps[i] > 1.5 * c.tau0_s) {
      runs.push_back({rate_dph.subspan(start, i + 1 - start), {}});
      c.longest_run_s = std::max(c.longest_run_s, time_s[i] - time_s[start] + c.tau0_s);
      start = i + 1;
    }
  }
  c.runs = runs.size();
  c.gaps = runs.size() - 1;
  std::size_t longest_run = 0;
  for (Run& r : runs) {
    r.angle = angle_of(r.rate);
    longest_run = std::max(longest_run, r.rate.size());
  }
  const auto by_share = static_cast<std::size_t>(options.longest_share * (c.span_s + c.tau0_s) / c.tau0_s);
  std::size_t largest = std::min(by_share, longest_run / 2);
  c.limited_by_runs = longest_run / 2 < by_share;
  if (options.tau_max_s > 0.0) {
    const auto asked = static_cast<std::size_t>(std::floor(options.tau_max_s / c.tau0_s + 1e-9));
    if (asked > longest_run / 2)
      throw InputError(fmt::format("--tau-max {} s: a τ needs one gap-free stretch of 2τ, and the longest in {} is "
                                   "{:.6g} s ({} of {:.6g} s); the longest τ it can give is {:.6g} s",
                                   options.tau_max_s, c.name, c.longest_run_s, counted(longest_run, "sample"), c.tau0_s,
                                   static_cast<double>(longest_run / 2) * c.tau0_s));
    if (asked < 1)
      throw InputError(fmt::format("--tau-max {} s is shorter than the sample interval {:.6g} s", options.tau_max_s,
                                   c.tau0_s));
    largest = asked;
    c.limited_by_runs = false;
  }
  if (largest < 1)
    throw InputError(fmt::format("{}: no gap-free stretch of 2 samples at the sample interval {} s; "
                                 "the record cannot give an Allan deviation",
                                 c.name, c.tau0_s));
  if (options.spacing == TauSpacing::all && static_cast<double>(n) * static_cast<double>(largest) > 5e9)
    throw InputError(fmt::format("--taus all on {} samples would compute {} τ of {} terms each; "
                                 "use --taus octave or decade",
                                 n, largest, n));
  for (const std::size_t m : factors(options.spacing, largest)) {
    AllanRow row;
    row.m = m;
    row.tau_s = static_cast<double>(m) * c.tau0_s;
    double sum = 0.0;
    for (const Run& r : runs) {
      const auto [s, t] = second_differences(r.angle, m);
      sum += s;
      row.terms += t;
    }
    if (row.terms == 0) continue;
    const std::size_t contiguous = n >= 2 * m ? n - 2 * m + 1 : 0;
    row.gap_terms = contiguous > row.terms ? contiguous - row.terms : 0;
    const double md = static_cast<double>(m);
    row.adev_dph = std::sqrt(sum / (2.0 * md * md * static_cast<double>(row.terms)));
    row.alpha_from_acf = acf_alpha(runs, m, row.alpha);
    c.rows.push_back(row);
  }
  // Where the block averages are too few: the noise model's type, or the
  // curve's least-squares slope over the τ within two octaves.
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    AllanRow& row = c.rows[i];
    if (!row.alpha_from_acf) {
      double mu = -1.0;
      if (options.model_avar) {
        const double lo = options.model_avar(row.tau_s / 1.2), hi = options.model_avar(row.tau_s * 1.2);
        if (lo > 0.0 && hi > 0.0 && std::isfinite(lo) && std::isfinite(hi)) {
          mu = std::log(hi / lo) / std::log(1.44);
          row.alpha_from_model = true;
        }
      }
      if (!row.alpha_from_model) {
        if (const double slope = loglog_slope(c.rows, i, 2.0); !std::isnan(slope)) mu = 2.0 * slope;
      }
      row.alpha = std::clamp(static_cast<int>(std::lround(-mu - 1.0)), -2, 2);
    }
    for (const Run& r : runs)
      if (r.rate.size() >= 2 * row.m) row.edf += greenhall_edf(row.alpha, row.m, r.rate.size() + 1);
    row.edf = std::max(row.edf, 1.0);
    const boost::math::chi_squared chi2(row.edf);
    row.lo_dph = row.adev_dph * std::sqrt(row.edf / boost::math::quantile(chi2, 0.5 + 0.5 * options.confidence));
    row.hi_dph = row.adev_dph * std::sqrt(row.edf / boost::math::quantile(chi2, 0.5 - 0.5 * options.confidence));
  }
  return c;
}

}  // namespace gyrotherm::studies
