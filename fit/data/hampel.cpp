#include "fit/data/hampel.h"

#include <algorithm>
#include <cmath>

#include "fit/data/median.h"

namespace gyrotherm::fit {

void HampelWindow::push(double x) {
  const std::uint64_t seq = first_ + values_.size();
  values_.push_back(x);
  while (!lowest_.empty() && lowest_.back().second >= x) lowest_.pop_back();
  lowest_.push_back({seq, x});
  while (!highest_.empty() && highest_.back().second <= x) highest_.pop_back();
  highest_.push_back({seq, x});
  if (sorting_) sorted_.insert(x, seq);
}

void HampelWindow::pop() {
  if (sorting_) sorted_.erase(values_.front(), first_);
  values_.pop_front();
  ++first_;
  while (!lowest_.empty() && lowest_.front().first < first_) lowest_.pop_front();
  while (!highest_.empty() && highest_.front().first < first_) highest_.pop_front();
}

HampelWindow::Verdict HampelWindow::judge(double x, bool want_scale) {
  const std::size_t n = values_.size();
  const double bound = rule_.bound();
  if (!want_scale) {
    // Every value within the bound of x (with a margin for rounding): so is
    // their median, and x is kept. Most samples end here.
    const double margin = bound * (1.0 - 1e-9);
    if (highest_.front().second - x <= margin && x - lowest_.front().second <= margin) {
      if (sorting_ && ++clean_ > n) {  // long clear of any glitch: stop sorting
        sorting_ = false;
        sorted_.clear();
      }
      return {};
    }
    clean_ = 0;
    if (!sorting_) {  // near a glitch: keep the window in order for a while
      sorting_ = true;
      for (std::size_t i = 0; i < n; ++i) sorted_.insert(values_[i], first_ + i);
    }
  }
  // (A sample given the full test for the report alone gets its median and MAD by selection.)
  double median = 0.0;
  if (sorting_) {
    median = sorted_.median();
  } else {
    scratch_.resize(n);
    for (std::size_t i = 0; i < n; ++i) scratch_[i] = values_[i];
    median = median_in_place(scratch_);
  }
  const double deviation = std::abs(x - median);
  if (!want_scale && !(deviation > bound)) return {};
  double mad = 0.0;
  if (sorting_) {
    mad = sorted_.median_abs_deviation(median);
  } else {
    for (std::size_t i = 0; i < n; ++i) scratch_[i] = std::abs(values_[i] - median);
    mad = median_in_place(scratch_);
  }
  Verdict v;
  v.scaled = true;
  v.scale = std::max(kMadToSigma * mad, rule_.floor_dph);
  v.glitch = deviation > rule_.threshold * v.scale && deviation > rule_.zero_dph;
  return v;
}

bool TrailingHampel::is_glitch(double t, double x) {
  while (!times_.empty() && t - times_.front() > window_s_) {
    times_.pop_front();
    window_.pop();
  }
  times_.push_back(t);
  window_.push(x);
  return window_.size() >= 3 && window_.judge(x, false).glitch;
}

}  // namespace gyrotherm::fit
