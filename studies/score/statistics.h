#pragma once
// Order statistics and intervals for Monte Carlo scoreboards (studies/score/).
//
// Medians and percentiles interpolate between order statistics (Hyndman–Fan
// definition 7); a trial that did not reach the target counts as +∞, so a
// median of +∞ means "not reached". 95 % intervals need no distributional
// assumption:
//
//  * a median: the order statistics [x_(j), x_(n+1−j)], j the largest with
//    P(Bin(n, ½) < j) ≤ 0.025 (coverage ≥ 95 %; [min, max] when n < 6);
//  * a success rate: Wilson's score interval for x successes in n.
//
// References: H. A. David, H. N. Nagaraja, "Order Statistics", 3rd ed.,
// Wiley 2003, §7.1 (distribution-free intervals for quantiles); E. B. Wilson,
// "Probable inference, the law of succession, and statistical inference",
// JASA 22 (1927) 209–212; Hyndman & Fan, "Sample quantiles in statistical
// packages", Am. Stat. 50 (1996) (definition 7).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace gyrotherm::studies {

struct Range {
  double low = 0.0;
  double high = 0.0;
};
// Hyndman–Fan definition 7 on sorted values; +∞ values allowed (the result is
// +∞ when an infinite value takes part).
double quantile(std::span<const double> sorted, double p);
// Distribution-free 95 % interval of the median of sorted values.
Range median_interval(std::span<const double> sorted);
// Wilson's 95 % score interval of a proportion.
Range wilson_interval(std::size_t successes, std::size_t n);

struct Summary {
  double median = 0.0;
  double p10 = 0.0;
  double p90 = 0.0;
  Range median_ci;  // 95 %
};


// Median, 10th and 90th percentiles and the median's interval of any values.
Summary summary_of(std::vector<double> values);

// A value for people: formatted with `spec`, or "not reached" when it is +∞.
std::string format_value(double v, const char* spec = "{:.4g}");

}  // namespace gyrotherm::studies
