#pragma once
// Hampel's test, the one glitch rule behind every glitch filter: the offline
// one (fit/data/outliers.h), the one-pass reader of large logs
// (fit/data/streaming.h) and the real-time compensator
// (fit/causal_compensator.h). `export --format c` writes the same test in C
// (studies/export/c_header.cpp), and its tests hold it to the compensator.
//
// Over the values x_j of a sample's window (the sample among them):
//
//   m = median_j x_j,                            the moving median,
//   s = max(1.4826 · median_j |x_j − m|, s_floor),  the local MAD, floored,
//   the sample is a glitch  ⇔  |x − m| > t · s  and  |x − m| > z,
//
// t the threshold, s_floor the record's noise floor (fit/data/outliers.h), z
// the round-off level below which differences count as 0. A window of fewer
// than 3 values judges nothing.
//
// Most samples are far from any glitch: a sample within t · s_floor of every
// value of its window is within it of their median too, so it is kept without
// the median, in O(1), from the window's running minimum and maximum
// (monotone queues). Near a glitch the window is kept in order for a while (an
// order-statistic tree, fit/data/order_statistic_tree.h), so that the median
// and the MAD cost O(log w) and O(log² w) for a window of w samples, and each
// sample entering or leaving O(log w).
//
// The windows: centred, ±W/2 around the sample (offline and one-pass:
// CentredHampel, which judges a sample once the samples after it have
// arrived), or trailing, the last W seconds up to the sample (real time:
// TrailingHampel).
//
// References: F. R. Hampel, "The influence curve and its role in robust
// estimation", JASA 69 (1974); R. K. Pearson, "Outliers in process modeling and
// identification", IEEE Trans. Control Syst. Technol. 10(1):55-63 (2002);
// Pearson et al., "Generalized Hampel filters", EURASIP J. Adv. Signal Process.
// 2016:87.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "fit/data/order_statistic_tree.h"
#include "fit/data/ring_buffer.h"

namespace gyrotherm::fit {

inline constexpr double kMadToSigma = 1.4826;  // 1/Φ⁻¹(3/4): MAD of N(0, σ²) is σ/1.4826

struct HampelRule {
  double threshold = 8.0;  // t
  double floor_dph = 0.0;  // s_floor
  double zero_dph = 0.0;   // z
  double bound() const { return threshold * floor_dph; }
};

// The values of a sliding window, oldest first, and the test of one of them.
class HampelWindow {
 public:
  explicit HampelWindow(const HampelRule& rule) : rule_(rule) {}

  void push(double x);
  void pop();  // the oldest leaves
  std::size_t size() const { return values_.size(); }

  struct Verdict {
    bool glitch = false;
    bool scaled = false;  // s was computed (`scale` holds it)
    double scale = 0.0;
  };
  // Judges x, a value of the window. With `want_scale` the full test runs and
  // s is returned (the reports' noise scale is a median of such s).
  Verdict judge(double x, bool want_scale);

 private:
  HampelRule rule_;
  RingBuffer<double> values_;
  std::uint64_t first_ = 0;  // the sequence number of values_.front()
  RingBuffer<std::pair<std::uint64_t, double>> lowest_, highest_;
  // Near a glitch: the values in order, until the shortcut has kept a
  // window's worth of samples in a row.
  bool sorting_ = false;
  OrderStatisticTree sorted_;
  std::size_t clean_ = 0;
  std::vector<double> scratch_;
};

// The centred window ±W/2, fed samples in time order. judged(payload, kept)
// is called for each sample, in order, once the samples after it that belong
// to its window have arrived (all of them by finish()). Every `report_stride`-th
// sample (counted from 0) is given the full test and its s kept in scales().
template <class Payload>
class CentredHampel {
 public:
  CentredHampel(const HampelRule& rule, double window_s, std::size_t report_stride)
      : window_(rule), half_s_(0.5 * window_s), stride_(report_stride) {}

  template <class Judged>
  void add(double t, double x, Payload payload, Judged&& judged) {
    pending_.push_back(Entry{t, x, std::move(payload)});
    advance(false, judged);
  }
  template <class Judged>
  void finish(Judged&& judged) {
    advance(true, judged);
  }
  std::vector<double>& scales() { return scales_; }

 private:
  struct Entry {
    double t, x;
    Payload payload;
  };
  // pending_ holds the samples from lo_ on (absolute indices from base_):
  // the window's members lo_ … hi_ − 1 and those not yet in it.
  template <class Judged>
  void advance(bool flush, Judged& judged) {
    const std::size_t end = base_ + pending_.size();
    while (next_ < end) {
      const double t_k = at(next_).t;
      for (; hi_ < end && at(hi_).t - t_k <= half_s_; ++hi_) window_.push(at(hi_).x);
      if (hi_ == end && !flush) return;  // a later sample may still belong
      for (; t_k - at(lo_).t > half_s_; ++lo_) window_.pop();
      const bool sampled = next_ % stride_ == 0;
      const HampelWindow::Verdict v = window_.size() < 3 ? HampelWindow::Verdict{} : window_.judge(at(next_).x, sampled);
      if (v.scaled && sampled) scales_.push_back(v.scale);
      judged(at(next_).payload, !v.glitch);
      ++next_;
      for (; base_ < lo_; ++base_) pending_.pop_front();
    }
  }
  const Entry& at(std::size_t k) const { return pending_[k - base_]; }

  HampelWindow window_;
  double half_s_;
  std::size_t stride_;
  RingBuffer<Entry> pending_;
  std::size_t base_ = 0, lo_ = 0, hi_ = 0, next_ = 0;
  std::vector<double> scales_;
};

// The trailing window: the samples of the last W seconds up to this one.
class TrailingHampel {
 public:
  TrailingHampel(const HampelRule& rule, double window_s) : window_(rule), window_s_(window_s) {}
  // True if the sample is a glitch.
  bool is_glitch(double t, double x);

 private:
  HampelWindow window_;
  double window_s_;
  RingBuffer<double> times_;
};

}  // namespace gyrotherm::fit
