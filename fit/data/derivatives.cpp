#include "fit/data/derivatives.h"

namespace gyrotherm::fit {
namespace {

// Central differences within each run (one-sided at its ends), or backward
// differences (0 at the first window of a run) for the causal mode.
std::vector<double> differentiate(const std::vector<double>& t_s, const std::vector<double>& x,
                                  const std::vector<std::size_t>& run, DerivativeMode mode) {
  const std::size_t n = x.size();
  std::vector<double> d(n, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const bool has_prev = p > 0 && run[p - 1] == run[p];
    const bool has_next = p + 1 < n && run[p + 1] == run[p];
    std::size_t lo = p, hi = p;
    if (mode == DerivativeMode::causal) {
      if (has_prev) lo = p - 1;
    } else {
      if (has_prev) lo = p - 1;
      if (has_next) hi = p + 1;
    }
    if (hi != lo) d[p] = (x[hi] - x[lo]) / (t_s[hi] - t_s[lo]);
  }
  return d;
}

}  // namespace

const char* to_string(DerivativeMode mode) { return mode == DerivativeMode::causal ? "causal" : "central"; }

DerivedSeries derive(const AveragedSeries& data, DerivativeMode mode) {
  DerivedSeries d;
  d.temp_c = data.temp_c;
  d.temp2_c = data.temp2_c;
  d.time_s.reserve(data.size());
  for (double t : data.time_s) d.time_s.push_back(t - data.start_time_s);
  d.switch_on_s = 0.0;
  d.rate_c_per_s = differentiate(data.time_s, data.temp_c, data.run, mode);
  d.accel_c_per_s2 = differentiate(data.time_s, d.rate_c_per_s, data.run, mode);
  return d;
}

}  // namespace gyrotherm::fit
