#include "sim/allan.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <unordered_set>

#include <boost/math/distributions/chi_squared.hpp>

namespace gyrotherm::sim {

namespace {

// Tails of the ±1σ band of a normal distribution: Φ(−1) and Φ(1).
constexpr double kLowerTail = 0.15865525393145705;
constexpr double kUpperTail = 0.8413447460685429;

// Equivalent degrees of freedom of the overlapping Allan variance for white FM
// noise (Howe, Allan & Barnes 1981; NIST SP 1065, Table 5), N phase points.
double white_fm_edf(std::size_t rate_samples, std::size_t m) {
  const double n_phase = static_cast<double>(rate_samples) + 1.0;
  const double md = static_cast<double>(m);
  return (3.0 * (n_phase - 1.0) / (2.0 * md) - 2.0 * (n_phase - 2.0) / n_phase) * 4.0 * md * md /
         (4.0 * md * md + 5.0);
}

}  // namespace

std::vector<AllanPoint> allan_deviation(std::span<const double> rate, double dt_s,
                                        std::span<const double> tau_s) {
  assert(dt_s > 0.0);
  const std::size_t n = rate.size();
  std::vector<AllanPoint> points;
  if (n < 2) return points;

  // 1. Phase in units of (rate × samples), x_k = Σ_{i<k} (y_i − ȳ). Removing the
  //    mean leaves σ² unchanged (it cancels in the second difference) and keeps
  //    x small; compensated (Neumaier) summation keeps each x_k within half an
  //    ulp, so long series lose no digits in the second differences.
  double mean = 0.0;
  {
    double sum = 0.0, carry = 0.0;
    for (double y : rate) {
      const double t = sum + y;
      carry += std::abs(sum) >= std::abs(y) ? (sum - t) + y : (y - t) + sum;
      sum = t;
    }
    mean = (sum + carry) / static_cast<double>(n);
  }
  std::vector<double> phase(n + 1);
  {
    double sum = 0.0, carry = 0.0;
    phase[0] = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double y = rate[i] - mean;
      const double t = sum + y;
      carry += std::abs(sum) >= std::abs(y) ? (sum - t) + y : (y - t) + sum;
      sum = t;
      phase[i + 1] = sum + carry;
    }
  }

  std::unordered_set<std::size_t> done;
  for (double tau : tau_s) {
    // 2. Round τ to m samples; drop what cannot be estimated.
    const double ratio = tau / dt_s;
    if (!(ratio >= 0.5) || !(ratio <= static_cast<double>(n))) continue;
    const auto m = static_cast<std::size_t>(std::llround(ratio));
    if (m < 1 || n / m < 2 || !done.insert(m).second) continue;

    // 3. Overlapping second differences of the phase.
    const std::size_t terms = n - 2 * m + 1;
    double sum_sq = 0.0;
    for (std::size_t j = 0; j < terms; ++j) {
      const double d = phase[j + 2 * m] - 2.0 * phase[j + m] + phase[j];
      sum_sq += d * d;
    }
    const double md = static_cast<double>(m);
    const double avar = sum_sq / (2.0 * md * md * static_cast<double>(terms));

    // 4. χ² confidence band.
    const double edf = white_fm_edf(n, m);
    const boost::math::chi_squared_distribution<double> chi2(edf);
    const double deviation = std::sqrt(avar);
    AllanPoint point;
    point.tau_s = md * dt_s;
    point.deviation = deviation;
    point.lower = deviation * std::sqrt(edf / boost::math::quantile(chi2, kUpperTail));
    point.upper = deviation * std::sqrt(edf / boost::math::quantile(chi2, kLowerTail));
    point.clusters = n / m;
    points.push_back(point);
  }
  return points;
}

std::vector<double> octave_taus(std::size_t samples, double dt_s, int per_decade) {
  assert(dt_s > 0.0 && per_decade >= 1);
  std::vector<double> taus;
  const double m_max = static_cast<double>(samples) / 10.0;
  std::size_t last_m = 0;
  for (int k = 0;; ++k) {
    const double m_exact = std::pow(10.0, static_cast<double>(k) / per_decade);
    // A little slack so that an exact power of ten at the end is kept.
    if (m_exact > m_max * (1.0 + 1e-12)) break;
    const auto m = static_cast<std::size_t>(std::llround(m_exact));
    if (m > last_m && static_cast<double>(m) <= m_max) {
      taus.push_back(static_cast<double>(m) * dt_s);
      last_m = m;
    }
  }
  return taus;
}

}  // namespace gyrotherm::sim
