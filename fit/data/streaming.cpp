#include "fit/data/streaming.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>

#include "sim/util/input_error.h"
#include "sim/util/random.h"

namespace gyrotherm::fit {
namespace {

constexpr double kMadToSigma = 1.4826;

// Vitter's algorithm R with a fixed seed.
class Reservoir {
 public:
  explicit Reservoir(std::size_t capacity, std::uint64_t stream)
      : capacity_(capacity), rng_(make_rng(streams::reservoir_seed, stream)) {}
  void add(double v) {
    ++seen_;
    if (values_.size() < capacity_) {
      values_.push_back(v);
      return;
    }
    const std::uint64_t j = rng_() % seen_;
    if (j < capacity_) values_[static_cast<std::size_t>(j)] = v;
  }
  std::vector<double>& values() { return values_; }

 private:
  std::size_t capacity_;
  Rng rng_;
  std::uint64_t seen_ = 0;
  std::vector<double> values_;
};

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2 == 1) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

// Median of a sliding multiset of values: lower half in `low`, upper in `high`,
// |low| = |high| or |high| + 1.
class RollingMedian {
 public:
  void insert(double v) {
    if (low_.empty() || v <= *low_.rbegin())
      low_.insert(v);
    else
      high_.insert(v);
    rebalance();
  }
  void erase(double v) {
    auto it = low_.find(v);
    if (it != low_.end() && v <= *low_.rbegin()) {
      low_.erase(it);
    } else {
      high_.erase(high_.find(v));
    }
    rebalance();
  }
  double median() const {
    if (low_.size() > high_.size()) return *low_.rbegin();
    return 0.5 * (*low_.rbegin() + *high_.begin());
  }
  std::size_t size() const { return low_.size() + high_.size(); }

 private:
  void rebalance() {
    while (low_.size() > high_.size() + 1) {
      high_.insert(*low_.rbegin());
      low_.erase(std::prev(low_.end()));
    }
    while (high_.size() > low_.size()) {
      low_.insert(*high_.begin());
      high_.erase(high_.begin());
    }
  }
  std::multiset<double> low_, high_;
};

struct Sample {
  double t, temp, gyro, temp2;
  std::size_t run;
};

}  // namespace

PreparedData prepare_data_streaming(const std::filesystem::path& csv, const PipelineOptions& o) {
  o.outliers.validate();
  // Pass 1: sample interval and noise floor.
  Reservoir steps(20000, streams::reservoir_steps), jumps(20000, streams::reservoir_jumps);
  double previous_t = 0.0, previous_x = 0.0, largest = 0.0, smallest_jump = INFINITY;
  bool first = true;
  const CsvHeader header = for_each_row(csv, o.columns, [&](double t, double, double x, double) {
    largest = std::max(largest, std::abs(x));
    if (!first) {
      steps.add(t - previous_t);
      const double jump = std::abs(x - previous_x);
      jumps.add(jump);
      if (jump > 0.0) smallest_jump = std::min(smallest_jump, jump);
    }
    first = false;
    previous_t = t;
    previous_x = x;
  });
  const double interval = median_of(steps.values());
  std::vector<double>& j = jumps.values();
  for (double& v : j)
    if (v < 1e-9 * largest) v = 0.0;
  double floor = kMadToSigma * median_of(j) / std::sqrt(2.0);
  if (!(floor > 0.0)) floor = std::isfinite(smallest_jump) ? smallest_jump : 0.0;

  // Pass 2: streaming Hampel filter into the window averager.
  PreparedData d;
  d.file = header.file;
  d.raw_samples = header.rows;
  d.outliers.floor_dph = floor;
  WindowAverager averager(o.averaging, interval, header.has_temp2);
  const double half = 0.5 * o.outliers.window_s;
  const double gap = o.averaging.gap_factor * interval;
  std::deque<Sample> window;  // samples from (judged − W/2) to the newest
  std::size_t next = 0;       // index in `window` of the next sample to judge
  RollingMedian median;
  std::size_t run = 0;
  double last_t = -INFINITY;
  std::vector<double> scratch;
  std::vector<double> scales;

  auto judge = [&](std::size_t k) {
    const Sample& s = window[k];
    // The window of s: same run, within ±W/2 (the multiset holds exactly those).
    bool valid = true;
    if (o.remove_outliers && median.size() >= 3) {
      const double m = median.median();
      const double deviation = std::abs(s.gyro - m);
      if (deviation > o.outliers.threshold * floor) {
        scratch.clear();
        for (const Sample& w : window)
          if (w.run == s.run && std::abs(w.t - s.t) <= half) scratch.push_back(std::abs(w.gyro - m));
        const double scale = std::max(kMadToSigma * median_of(scratch), floor);
        valid = deviation <= o.outliers.threshold * scale;
      }
    }
    if (!valid) {
      ++d.outliers.removed;
      d.outliers.times_s.push_back(s.t);
    }
    averager.add(s.t, s.temp, s.gyro, s.temp2, valid);
  };
  // The multiset holds the samples of window[lo, hi) that are within ±W/2 of
  // window[next] and in its run.
  std::size_t lo = 0, hi = 0;
  auto advance = [&](bool flush) {
    while (next < window.size()) {
      const Sample& s = window[next];
      // Add everything up to s.t + W/2 (in its run); stop if not arrived yet.
      while (hi < window.size() && window[hi].run == s.run && window[hi].t <= s.t + half) {
        median.insert(window[hi].gyro);
        ++hi;
      }
      if (!flush && hi == window.size()) return;  // a later sample may still belong
      while (lo < hi && (window[lo].run != s.run || window[lo].t < s.t - half)) {
        median.erase(window[lo].gyro);
        ++lo;
      }
      judge(next);
      ++next;
      // Samples before lo left the multiset and no later window reaches
      // back to them (lo ≤ next always): drop them.
      while (lo > 0) {
        window.pop_front();
        --lo;
        --hi;
        --next;
      }
    }
  };
  for_each_row(csv, o.columns, [&](double t, double temp, double gyro, double temp2) {
    if (t - last_t > gap) ++run;
    last_t = t;
    window.push_back({t, temp, gyro, temp2, run});
    advance(false);
  });
  advance(true);
  d.series = averager.finish();
  d.averaging = averager.report();
  d.derived = derive(d.series, o.derivative, o.derivative_span_s);
  d.derivative_span_s = o.derivative_span_s;
  return d;
}

PreparedData prepare_csv(const std::filesystem::path& csv, const PipelineOptions& options,
                         bool* streamed) {
  std::error_code size_error;
  const auto bytes = std::filesystem::file_size(csv, size_error);
  // Log columns as model terms need the record in memory.
  const bool stream = !size_error && bytes > kStreamingThresholdBytes && options.columns.extra.empty() &&
                      !options.columns.other_numeric;
  if (streamed != nullptr) *streamed = stream;
  return stream ? prepare_data_streaming(csv, options) : prepare_data(csv, options);
}

}  // namespace gyrotherm::fit
