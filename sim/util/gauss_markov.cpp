#include "sim/util/gauss_markov.h"

#include <algorithm>
#include <cmath>

namespace gyrotherm {

double gauss_markov_allan_shape(double x) {
  if (x < 2.0) {
    //   2x − 3 + 4e^{−x} − e^{−2x} = Σ_{n≥3} (−1)^n (4 − 2^n) xⁿ / n!;
    // for x < 2 the terms fall below 1e-17 of the sum well before n = 40.
    double sum = 0.0;
    double x_pow_over_fact = x * x * x / 6.0;  // xⁿ/n! at n = 3
    double two_pow = 8.0;
    double sign = -1.0;
    for (int n = 3; n < 60; ++n) {
      const double term = sign * (4.0 - two_pow) * x_pow_over_fact;
      sum += term;
      if (std::abs(term) < 1e-18 * std::abs(sum)) break;
      x_pow_over_fact *= x / (n + 1);
      two_pow *= 2.0;
      sign = -sign;
    }
    return sum / (x * x);
  }
  const double e1 = std::exp(-x);
  return (2.0 * x - 3.0 + 4.0 * e1 - e1 * e1) / (x * x);
}

double bank_allan_peak(std::span<const double> taus, double from_s, double to_s, int steps) {
  double peak = 0.0;
  for (int j = 0; j <= steps; ++j) {
    const double tau = steps == 0 ? from_s : from_s * std::pow(to_s / from_s, static_cast<double>(j) / steps);
    double avar = 0.0;
    for (const double t : taus) avar += gauss_markov_allan_shape(tau / t);
    peak = std::max(peak, avar);
  }
  return peak;
}

}  // namespace gyrotherm
