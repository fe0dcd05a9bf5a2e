#include "studies/score/statistics.h"
#include "sim/util/numbers.h"

#include <boost/math/distributions/binomial.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace gyrotherm::studies {

double quantile(std::span<const double> sorted, double p) {
  assert(!sorted.empty() && p >= 0.0 && p <= 1.0);
  const double h = static_cast<double>(sorted.size() - 1) * p;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  const double w = h - static_cast<double>(lo);
  if (w == 0.0 || lo == hi) return sorted[lo];
  if (!std::isfinite(sorted[hi]) || !std::isfinite(sorted[lo])) return std::numeric_limits<double>::infinity();
  return sorted[lo] + w * (sorted[hi] - sorted[lo]);
}

Range median_interval(std::span<const double> sorted) {
  assert(!sorted.empty());
  const std::size_t n = sorted.size();
  // The largest j with P(B ≤ j − 1) ≤ 0.025, B ~ Bin(n, ½): then
  // P(x_(j) ≤ median ≤ x_(n+1−j)) ≥ 1 − 2·P(B ≤ j − 1) ≥ 0.95.
  const boost::math::binomial_distribution<double> b(static_cast<double>(n), 0.5);
  std::size_t j = 0;
  while (j + 1 <= n / 2 && boost::math::cdf(b, static_cast<double>(j)) <= 0.025) ++j;
  if (j == 0) return {sorted.front(), sorted.back()};  // n < 6: no 95 % interval exists
  return {sorted[j - 1], sorted[n - j]};
}

Range wilson_interval(std::size_t successes, std::size_t n) {
  assert(n > 0 && successes <= n);
  constexpr double z = kZ95;
  const double nn = static_cast<double>(n);
  const double p = static_cast<double>(successes) / nn;
  const double denominator = 1.0 + z * z / nn;
  const double centre = (p + z * z / (2.0 * nn)) / denominator;
  const double half = z / denominator * std::sqrt(p * (1.0 - p) / nn + z * z / (4.0 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

Summary summary_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  Summary s;
  s.median = quantile(v, 0.5);
  s.p10 = quantile(v, 0.1);
  s.p90 = quantile(v, 0.9);
  s.median_ci = median_interval(v);
  return s;
}

std::string format_value(double v, const char* spec) {
  return std::isfinite(v) ? fmt::format(fmt::runtime(spec), v) : std::string("not reached");
}

}  // namespace gyrotherm::studies
