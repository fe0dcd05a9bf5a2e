#include "fit/data/edge_rate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gyrotherm::fit {
namespace {

// The least-squares line through (t, x), evaluated at `at`.
double line_at(const std::vector<double>& t, const std::vector<double>& x, double at) {
  const auto n = static_cast<double>(t.size());
  double mt = 0.0, mx = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    mt += t[i];
    mx += x[i];
  }
  mt /= n;
  mx /= n;
  double stt = 0.0, stx = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    stt += (t[i] - mt) * (t[i] - mt);
    stx += (t[i] - mt) * (x[i] - mx);
  }
  return stt > 0.0 ? mx + stx / stt * (at - mt) : mx;
}

}  // namespace

EdgeRate::EdgeRate(std::size_t k, double sample_interval_s) : k_(std::max<std::size_t>(2, k)), interval_s_(sample_interval_s) {
  first_t_.reserve(k_);
  first_x_.reserve(k_);
  last_t_.assign(k_, 0.0);
  last_x_.assign(k_, 0.0);
}

std::size_t EdgeRate::samples_for(double window_s, double sample_interval_s) {
  const double k = std::round(0.05 * window_s / sample_interval_s);
  return static_cast<std::size_t>(std::clamp(k, 2.0, 64.0));
}

void EdgeRate::add(double time_s, double value) {
  if (first_t_.size() < k_) {
    first_t_.push_back(time_s);
    first_x_.push_back(value);
  }
  last_t_[count_ % k_] = time_s;
  last_x_[count_ % k_] = value;
  ++count_;
}

double EdgeRate::rate() const {
  if (count_ < 2 * k_) return std::numeric_limits<double>::quiet_NaN();
  const double from = first_t_.front() - interval_s_ / 2.0;
  const double to = last_t_[(count_ - 1) % k_] + interval_s_ / 2.0;
  return (line_at(last_t_, last_x_, to) - line_at(first_t_, first_x_, from)) / (to - from);
}

void EdgeRate::reset() {
  first_t_.clear();
  first_x_.clear();
  count_ = 0;
}

}  // namespace gyrotherm::fit
