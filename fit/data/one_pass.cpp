// The one-pass preparation (fit/data/one_pass.h, fit/data/streaming.h).
#include "fit/data/one_pass.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "fit/data/median.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit::one_pass {

PreparedData Preparer::finish() {
  if (!averager_) begin_stream(true);
  if (filter_) filter_->finish([this](const Row& r, bool kept) { judged(r, kept); });
  d_.series = averager_->finish();
  d_.averaging = averager_->report();
  d_.outliers.removed = d_.outliers.times_s.size();
  d_.outliers.scale_dph =
      !filter_ || filter_->scales().empty() ? d_.outliers.floor_dph : median_in_place(filter_->scales());
  check_windows_survive(d_.file, d_.series, *averager_, o_.averaging);
  derive_into(d_, o_);
  d_.cautions = unit_cautions(d_.units, probe_.summary());
  return std::move(d_);
}

void Preparer::begin_stream(bool whole) {
  const std::size_t n = prefix_.size();
  if (n < 2)
    throw InputError(located(d_.file, 0, fmt::format("{} sample{}: averaging needs at least 2", n, n == 1 ? "" : "s")));
  std::vector<double> times(n), jumps(n - 1);
  double largest = std::abs(prefix_[0].gyro);
  times[0] = prefix_[0].t;
  for (std::size_t k = 1; k < n; ++k) {
    times[k] = prefix_[k].t;
    jumps[k - 1] = std::abs(prefix_[k].gyro - prefix_[k - 1].gyro);
    largest = std::max(largest, std::abs(prefix_[k].gyro));
  }
  rules_.interval_s = median_sample_interval_s(times);
  rules_.judge = o_.remove_outliers && n >= 3;
  if (rules_.judge) {
    rules_.zero_dph = kZeroRelative * largest;
    rules_.floor_dph = noise_floor_from_jumps(std::move(jumps), rules_.zero_dph);
  }
  rules_.bursts = in_bursts(times, rules_.interval_s, o_.averaging);
  if (rules_.judge)  // the report's scale: as in memory for a record within the prefix, every 1000th sample otherwise
    filter_.emplace(HampelRule{o_.outliers.threshold, rules_.floor_dph, rules_.zero_dph}, o_.outliers.window_s,
                    whole ? std::max<std::size_t>(1, n / 10000) : 1000);

  d_.outliers.floor_dph = rules_.floor_dph;
  try {
    averager_.emplace(o_.averaging, rules_.interval_s, has_temp2_, rules_.bursts);
  } catch (const InputError& e) {
    throw InputError(located(d_.file, 0, e.what()));
  }
  std::vector<Row> prefix;
  prefix.swap(prefix_);  // released when replayed
  for (const Row& r : prefix) stream(r);
}

}  // namespace gyrotherm::fit::one_pass
