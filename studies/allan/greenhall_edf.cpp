#include "studies/allan/greenhall_edf.h"
#include "sim/util/numbers.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gyrotherm::studies {
namespace {

constexpr int kSecondDifference = 2;  // d: the Allan variance
constexpr double kJmax = 100.0;       // the largest basic sum computed term by term

// Eq. (7): the phase's generalised autocovariance for S_y ∝ f^α (up to a
// constant that cancels in the edf).
double sw(double t, int alpha) {
  const double a = std::abs(t);
  switch (alpha) {
    case 2: return -a;
    case 1: return a == 0.0 ? 0.0 : t * t * std::log(a);
    case 0: return a * a * a;
    case -1: return a == 0.0 ? 0.0 : t * t * t * t * std::log(a);
    default: return a * a * a * a * a;  // −2
  }
}

// Eq. (8): filtered by the τ-average (F = ∞: its limit, sw of α + 2).
double sx(double t, double f, int alpha) {
  if (f == kInfinity) return sw(t, alpha + 2);
  return f * f * (2.0 * sw(t, alpha) - sw(t - 1.0 / f, alpha) - sw(t + 1.0 / f, alpha));
}

// Eq. (9) for d = 2: the second difference's autocovariance.
double sz(double t, double f, int alpha) {
  return 6.0 * sx(t, f, alpha) - 4.0 * (sx(t - 1.0, f, alpha) + sx(t + 1.0, f, alpha)) + sx(t - 2.0, f, alpha) +
         sx(t + 2.0, f, alpha);
}

// Eq. (10): the basic sum, and 1/edf = BasicSum / (sz(0)² M).
double inverse_edf_by_sum(double j, double m_terms, double s, double f, int alpha) {
  double sum = std::pow(sz(0.0, f, alpha), 2) + (1.0 - j / m_terms) * std::pow(sz(j / s, f, alpha), 2);
  for (double k = 1.0; k < j; k += 1.0) sum += 2.0 * (1.0 - k / m_terms) * std::pow(sz(k / s, f, alpha), 2);
  return sum / (std::pow(sz(0.0, f, alpha), 2) * m_terms);
}

// Table 2 (d = 2): (a0, a1) of the large-sample limit, unmodified variance.
void table2(int alpha, double& a0, double& a1) {
  switch (alpha) {
    case 2: a0 = 35.0 / 18.0; a1 = 1.0; return;
    case 1: a0 = 790.0; a1 = 410.0; return;
    case 0: a0 = 2.0 / 3.0; a1 = 1.0 / 3.0; return;
    case -1: a0 = 0.852; a1 = 0.375; return;
    default: a0 = 1.079; a1 = 0.368; return;  // −2
  }
}

}  // namespace

double table5_edf(int alpha, double n, double m) {
  switch (alpha) {
    case 2:
      return (n + 1.0) * (n - 2.0 * m) / (2.0 * (n - m));
    case 1: {
      const double a = std::log((n - 1.0) / (2.0 * m)), b = std::log((2.0 * m + 1.0) * (n - 1.0) / 4.0);
      return a > 0.0 && b > 0.0 ? std::exp(std::sqrt(a * b)) : 1.0;
    }
    case 0:
      return (3.0 * (n - 1.0) / (2.0 * m) - 2.0 * (n - 2.0) / n) * 4.0 * m * m / (4.0 * m * m + 5.0);
    case -1:
      return m == 1.0 ? 2.0 * (n - 2.0) * (n - 2.0) / (2.3 * n - 4.9) : 5.0 * n * n / (4.0 * m * (n + 3.0 * m));
    default:  // −2
      return n > 3.0 ? (n - 2.0) / m * ((n - 1.0) * (n - 1.0) - 3.0 * m * (n - 1.0) + 4.0 * m * m) /
                           ((n - 3.0) * (n - 3.0))
                     : 1.0;
  }
}

double greenhall_edf(int alpha, std::size_t m_factor, std::size_t n_phase) {
  alpha = std::clamp(alpha, -2, 2);
  const double m = static_cast<double>(m_factor), n = static_cast<double>(n_phase);
  const double d = kSecondDifference;
  const double f = m, s = m;  // unmodified, overlapping
  const double length = m / f + m * d;  // the filter's span in phase samples
  const double m_terms = 1.0 + std::floor(s * (n - length) / m);
  if (m_terms < 1.0) return 1.0;
  const double j = std::min(m_terms, (d + 1.0) * s);
  const double r = m_terms / s;
  double inv = 0.0;
  if (alpha <= 0) {
    if (j <= kJmax) {
      inv = inverse_edf_by_sum(j, m_terms, s, kInfinity, alpha);  // the phase unfiltered (header)
    } else if (r > d + 1.0) {
      double a0 = 0, a1 = 0;
      table2(alpha, a0, a1);
      inv = (a0 - a1 / r) / r;
    } else {
      inv = inverse_edf_by_sum(kJmax, kJmax, kJmax / r, kInfinity, alpha);
    }
  } else if (alpha == 1) {
    // Table 3: b0 + b1 ln m normalises sz(0) for flicker phase noise.
    const double b = 15.23 + 12.0 * std::log(m);
    if (j <= kJmax) {
      inv = inverse_edf_by_sum(j, m_terms, s, m, 1);
    } else if (r > d + 1.0) {
      double a0 = 0, a1 = 0;
      table2(1, a0, a1);
      inv = (a0 - a1 / r) / (b * b * r);
    } else {
      const double mp = kJmax / r;
      double sum = 0.0;  // the basic sum without its normalisation, then b² in its place
      sum = inverse_edf_by_sum(kJmax, kJmax, mp, mp, 1) * std::pow(sz(0.0, mp, 1), 2) * kJmax;
      inv = sum / (b * b * kJmax);
    }
  } else {  // α = 2, white angle noise
    if (std::ceil(r) <= d) return std::max(1.0, table5_edf(2, n, m));
    inv = (35.0 / 18.0 - 0.5 * d / r) / m_terms;  // a0 = C(4d,2d)/C(2d,d)², a1 = d/2
  }
  return inv > 0.0 && std::isfinite(inv) ? std::max(1.0, 1.0 / inv) : 1.0;
}

}  // namespace gyrotherm::studies
