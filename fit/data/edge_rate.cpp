#include "fit/data/edge_rate.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gyrotherm::fit {
namespace {

struct Line {
  double value = 0, variance_factor = 0;  // at `at`; Var = σ²·variance_factor
};

// The least-squares line through (t, x), evaluated at `at`.
Line line_at(const std::vector<double>& t, const std::vector<double>& x, double at) {
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
  const double slope = stt > 0.0 ? stx / stt : 0.0;
  Line out;
  out.value = mx + slope * (at - mt);
  out.variance_factor = 1.0 / n + (stt > 0.0 ? (at - mt) * (at - mt) / stt : 0.0);
  return out;
}

}  // namespace

EdgeRate::EdgeRate(std::size_t k, double sample_interval_s) : k_(std::max<std::size_t>(2, k)), interval_s_(sample_interval_s) {
  first_t_.reserve(k_);
  first_x_.reserve(k_);
  last_t_.assign(k_, 0.0);
  last_x_.assign(k_, 0.0);
}

std::size_t EdgeRate::samples_for(double window_s, double sample_interval_s) {
  const double k = std::round(0.1 * window_s / sample_interval_s);
  return static_cast<std::size_t>(std::clamp(k, 3.0, 64.0));
}

void EdgeRate::add(double time_s, double value) {
  if (first_t_.size() < k_) {
    first_t_.push_back(time_s);
    first_x_.push_back(value);
  }
  last_t_[count_ % k_] = time_s;
  last_x_[count_ % k_] = value;
  if (count_ >= 2) second_differences_ += std::pow(value - 2.0 * latest_ + before_, 2);
  before_ = latest_;
  latest_ = value;
  ++count_;
}

double EdgeRate::rate() const {
  if (count_ < 2 * k_) return std::numeric_limits<double>::quiet_NaN();
  const double from = first_t_.front() - interval_s_ / 2.0;
  const double to = last_t_[(count_ - 1) % k_] + interval_s_ / 2.0;
  return (line_at(last_t_, last_x_, to).value - line_at(first_t_, first_x_, from).value) / (to - from);
}

double EdgeRate::standard_error() const {
  if (count_ < 2 * k_) return std::numeric_limits<double>::quiet_NaN();
  const double from = first_t_.front() - interval_s_ / 2.0;
  const double to = last_t_[(count_ - 1) % k_] + interval_s_ / 2.0;
  const Line a = line_at(first_t_, first_x_, from), b = line_at(last_t_, last_x_, to);
  const double variance = second_differences_ / (6.0 * static_cast<double>(count_ - 2));
  return std::sqrt(variance * (a.variance_factor + b.variance_factor)) / (to - from);
}

void EdgeRate::reset() {
  first_t_.clear();
  first_x_.clear();
  count_ = 0;
  second_differences_ = 0.0;
}

}  // namespace gyrotherm::fit
