#include "fit/data/outliers.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "fit/data/median.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

constexpr std::size_t kReportedScales =
    10000;  // OutlierReport::scale_dph is a median of about this many

// The members of the moving window, as a set of ranks 0 … n−1 (the samples'
// places in value order) in a Fenwick tree: insert, erase, count and select the
// k-th smallest member, each O(log n). Reference: P. M. Fenwick, "A new data
// structure for cumulative frequency tables", Softw. Pract. Exper. 24 (1994).
class RankSet {
 public:
  explicit RankSet(std::size_t n) : tree_(n + 1, 0), top_step_(std::bit_floor(n + 1)) {}

  void insert(std::size_t rank) { update(rank, +1); }
  void erase(std::size_t rank) { update(rank, -1); }

  // Members with rank < r.
  std::size_t count_below(std::size_t r) const {
    std::ptrdiff_t sum = 0;
    for (std::size_t i = r; i > 0; i &= i - 1) sum += tree_[i];
    return static_cast<std::size_t>(sum);
  }

  // Rank of the k-th smallest member, k = 1 … size.
  std::size_t select(std::size_t k) const {
    std::size_t position = 0;
    auto remaining = static_cast<std::ptrdiff_t>(k);
    for (std::size_t step = top_step_; step > 0; step >>= 1) {
      const std::size_t next = position + step;
      if (next < tree_.size() && tree_[next] < remaining) {
        position = next;
        remaining -= tree_[next];
      }
    }
    return position;  // 1-based index position + 1 ⇒ rank position
  }

 private:
  void update(std::size_t rank, std::ptrdiff_t delta) {
    for (std::size_t i = rank + 1; i < tree_.size(); i += i & (~i + 1)) tree_[i] += delta;
  }

  std::vector<std::ptrdiff_t> tree_;
  std::size_t top_step_;
};

// s_floor of the header, over consecutive samples valid on entry.
double noise_floor(const std::vector<double>& x, const std::vector<std::size_t>& used,
                   double zero) {
  std::vector<double> steps;
  steps.reserve(used.size());
  for (std::size_t p = 1; p < used.size(); ++p)
    steps.push_back(std::abs(x[used[p]] - x[used[p - 1]]));
  return noise_floor_from_jumps(std::move(steps), zero);
}

}  // namespace

double noise_floor_from_jumps(std::vector<double> jumps, double zero_dph) {
  if (jumps.empty()) return 0.0;
  double smallest = std::numeric_limits<double>::infinity();
  for (double d : jumps)
    if (d > zero_dph) smallest = std::min(smallest, d);
  const double median = median_in_place(jumps);
  if (median > zero_dph) return kMadToSigma * median / std::numbers::sqrt2;
  return std::isfinite(smallest) ? smallest : 0.0;
}

void OutlierOptions::validate() const {
  if (!(window_s > 0.0) || !std::isfinite(window_s))
    throw InputError(
        fmt::format("outlier window_s = {}: must be a finite number of seconds > 0", window_s));
  if (!(threshold > 0.0) || !std::isfinite(threshold))
    throw InputError(fmt::format(
        "--outlier-threshold {} (outlier threshold): must be a finite number > 0", threshold));
}

OutlierReport flag_outliers(const Measurement& m, const OutlierOptions& options,
                            std::vector<unsigned char>& valid) {
  options.validate();
  assert(valid.size() == m.size());
  const std::vector<double>& t = m.time_s;
  const std::vector<double>& x = m.gyro_dph;
  OutlierReport report;

  std::vector<std::size_t> used;  // samples valid on entry, in time order
  used.reserve(m.size());
  double largest = 0.0;
  for (std::size_t k = 0; k < m.size(); ++k)
    if (valid[k]) {
      used.push_back(k);
      largest = std::max(largest, std::abs(x[k]));
    }
  const std::size_t n = used.size();
  if (n < 3) return report;
  const double zero = kZeroRelative * largest;
  report.floor_dph = noise_floor(x, used, zero);

  // 1. Ranks in value (ties by time), so the window is a set of integers.
  std::vector<std::size_t> order(n);  // order[rank] = place in `used`
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return x[used[a]] < x[used[b]] || (x[used[a]] == x[used[b]] && a < b);
  });
  std::vector<std::size_t> rank_of(n);
  std::vector<double> sorted(n);
  for (std::size_t r = 0; r < n; ++r) {
    rank_of[order[r]] = r;
    sorted[r] = x[used[order[r]]];
  }

  RankSet window(n);
  const auto value = [&](std::size_t k) { return sorted[window.select(k)]; };  // k-th smallest
  const double half_s = 0.5 * options.window_s;
  const std::size_t report_stride = std::max<std::size_t>(1, n / kReportedScales);
  std::vector<double> scales;
  scales.reserve(n / report_stride + 1);
  std::size_t lo = 0, hi = 0;
  for (std::size_t p = 0; p < n; ++p) {
    // 2. Slide the window to [t_k − W/2, t_k + W/2].
    const double t_k = t[used[p]];
    for (; hi < n && t[used[hi]] - t_k <= half_s; ++hi) window.insert(rank_of[hi]);
    for (; t_k - t[used[lo]] > half_s; ++lo) window.erase(rank_of[lo]);
    const std::size_t size = hi - lo;
    if (size < 3) continue;

    // 3. The moving median.
    const double median =
        size % 2 == 1 ? value((size + 1) / 2) : 0.5 * (value(size / 2) + value(size / 2 + 1));

    // 4. The local MAD, only where it matters: the sample is beyond the floor's
    //    threshold, or it is one of the evenly spaced samples the report's
    //    scale is taken over (the MAD is most of the cost).
    const double deviation = std::abs(x[used[p]] - median);
    const bool sampled = p % report_stride == 0;
    if (!sampled && !(deviation > options.threshold * report.floor_dph)) continue;

    //    The k-th smallest |x_j − m| merges two sorted sequences,
    //    below(i) = m − (i-th member ≤ m counted downward), above(j) = (j-th member > m) − m.
    const std::size_t at_or_below = window.count_below(static_cast<std::size_t>(
        std::upper_bound(sorted.begin(), sorted.end(), median) - sorted.begin()));
    const std::size_t beyond = size - at_or_below;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const auto below = [&](std::size_t i) {
      return i == 0 ? -kInf : i > at_or_below ? kInf : median - value(at_or_below + 1 - i);
    };
    const auto above = [&](std::size_t j) {
      return j == 0 ? -kInf : j > beyond ? kInf : value(at_or_below + j) - median;
    };
    const auto kth_deviation = [&](std::size_t k) {
      std::size_t first = k > beyond ? k - beyond : 0, last = std::min(k, at_or_below);
      while (first < last) {  // smallest i with below(i + 1) ≥ above(k − i)
        const std::size_t i = first + (last - first) / 2;
        if (below(i + 1) < above(k - i))
          first = i + 1;
        else
          last = i;
      }
      return std::max(below(first), above(k - first));
    };
    const double mad = size % 2 == 1
                           ? kth_deviation((size + 1) / 2)
                           : 0.5 * (kth_deviation(size / 2) + kth_deviation(size / 2 + 1));

    // 5. Hampel's test against the larger of the local and the global scale.
    const double scale = std::max(kMadToSigma * mad, report.floor_dph);
    if (sampled) scales.push_back(scale);
    if (deviation > options.threshold * scale && deviation > zero) {
      valid[used[p]] = 0;
      report.times_s.push_back(t_k);
    }
  }
  report.removed = report.times_s.size();
  report.scale_dph = scales.empty() ? report.floor_dph : median_in_place(scales);
  return report;
}

}  // namespace gyrotherm::fit
