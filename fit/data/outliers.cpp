#include "fit/data/outliers.h"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

#include "fit/data/median.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

constexpr std::size_t kReportedScales =
    10000;  // OutlierReport::scale_dph is a median of about this many

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

  CentredHampel<std::size_t> filter({options.threshold, report.floor_dph, zero}, options.window_s,
                                    std::max<std::size_t>(1, n / kReportedScales));
  const auto judged = [&](std::size_t k, bool kept) {
    if (kept) return;
    valid[k] = 0;
    report.times_s.push_back(t[k]);
  };
  for (std::size_t k : used) filter.add(t[k], x[k], k, judged);
  filter.finish(judged);
  report.removed = report.times_s.size();
  report.scale_dph = filter.scales().empty() ? report.floor_dph : median_in_place(filter.scales());
  return report;
}

}  // namespace gyrotherm::fit
