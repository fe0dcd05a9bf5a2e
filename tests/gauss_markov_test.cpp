// The Allan variance of Gauss–Markov processes that sim/ and fit/ share
// (sim/util/gauss_markov.h): the closed form where it is exact, its series
// where the closed form cancels, and a bank's peak.

#include "sim/util/gauss_markov.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace gyrotherm {
namespace {

TEST(GaussMarkovAllan, ClosedFormWhereItHoldsItsDigitsSeriesBelow) {
  for (const double x : {2.0, 3.0, 10.0, 100.0}) {
    const double closed = (2.0 * x - 3.0 + 4.0 * std::exp(-x) - std::exp(-2.0 * x)) / (x * x);
    EXPECT_NEAR(gauss_markov_allan_shape(x), closed, 1e-15 * closed) << x;
  }
  // Near 2 both forms agree (the series is summed below 2, the closed form above).
  const long double x = 1.5L;
  const long double closed = (2.0L * x - 3.0L + 4.0L * std::exp(-x) - std::exp(-2.0L * x)) / (x * x);
  EXPECT_NEAR(gauss_markov_allan_shape(1.5), static_cast<double>(closed), 1e-14);
  // As x → 0: 2x/3 − x²/2 + 7x³/30 − …, where the closed form in double
  // precision has no digit left (at 1e-6 its numerator is 1e-18 of its terms).
  for (const double small : {1e-6, 1e-4, 1e-2}) {
    const double series = 2.0 * small / 3.0 - small * small / 2.0 + 7.0 * small * small * small / 30.0;
    EXPECT_NEAR(gauss_markov_allan_shape(small), series, 1e-6 * series) << small;
  }
}

TEST(GaussMarkovAllan, ABanksPeakIsTheGridsLargestSum) {
  // One process: its peak is at τ ≈ 1.89 T, Allan deviation 0.6174·σ.
  const std::vector<double> one = {100.0};
  EXPECT_NEAR(std::sqrt(bank_allan_peak(one, 1.0, 1e4, 800)), 0.61736, 2e-5);
  // Two processes a decade apart: the grid's largest sum, as summed here.
  const std::vector<double> two = {10.0, 100.0};
  double best = 0.0;
  for (int j = 0; j <= 400; ++j) {
    const double tau = 1.0 * std::pow(1e4, j / 400.0);
    best = std::max(best, gauss_markov_allan_shape(tau / 10.0) + gauss_markov_allan_shape(tau / 100.0));
  }
  EXPECT_DOUBLE_EQ(bank_allan_peak(two, 1.0, 1e4, 400), best);
  EXPECT_DOUBLE_EQ(bank_allan_peak(two, 5.0, 1e4, 0), gauss_markov_allan_shape(0.5) + gauss_markov_allan_shape(0.05));
}

}  // namespace
}  // namespace gyrotherm
