#include "fit/data/derivatives.h"

#include <cmath>

namespace gyrotherm::fit {
namespace {

// Central differences (one-sided where a neighbour is neither in the same
// gap-free run nor within span_s), or backward differences (0 without such
// an earlier window).
std::vector<double> differentiate(const std::vector<double>& t_s, const std::vector<double>& x,
                                  const std::vector<std::size_t>& run, DerivativeMode mode,
                                  double span_s) {
  const std::size_t n = x.size();
  std::vector<double> d(n, 0.0);
  const auto near = [&](std::size_t a, std::size_t b) {
    return run[a] == run[b] || t_s[b] - t_s[a] <= span_s;
  };
  for (std::size_t p = 0; p < n; ++p) {
    const bool has_prev = p > 0 && near(p - 1, p);
    const bool has_next = p + 1 < n && near(p, p + 1);
    std::size_t lo = p, hi = p;
    if (has_prev) lo = p - 1;
    if (mode == DerivativeMode::central && has_next) hi = p + 1;
    if (hi != lo) d[p] = (x[hi] - x[lo]) / (t_s[hi] - t_s[lo]);
  }
  return d;
}

// Where the series has a window's own rate from its edges (fit/data/edge_rate.h)
// and it differs from the difference of neighbouring windows by more than
// three standard errors (a ramp starts or ends near the window), it
// replaces it; the causal compensator keeps its backward differences (what
// export's C does).
// A window's edges disagree with the difference of means beyond their noise.
constexpr double kEdgeRateZ = 3.0;

void take_edge_rates(std::vector<double>& rate, const std::vector<double>& edges, const std::vector<double>& se,
                     DerivativeMode mode) {
  if (mode != DerivativeMode::central || edges.size() != rate.size() || se.size() != rate.size()) return;
  for (std::size_t p = 0; p < rate.size(); ++p)
    if (std::isfinite(edges[p]) && std::isfinite(se[p]) && std::abs(edges[p] - rate[p]) > kEdgeRateZ * se[p])
      rate[p] = edges[p];
}

}  // namespace

const char* to_string(DerivativeMode mode) { return mode == DerivativeMode::causal ? "causal" : "central"; }

DerivedSeries derive(const AveragedSeries& data, DerivativeMode mode, double span_s, double sensor_tau_s) {
  DerivedSeries d;
  d.temp_c = data.temp_c;
  d.temp2_c = data.temp2_c;
  d.time_s.reserve(data.size());
  for (double t : data.time_s) d.time_s.push_back(t - data.start_time_s);
  d.switch_on_s = 0.0;
  d.rate_c_per_s = differentiate(data.time_s, data.temp_c, data.run, mode, span_s);
  // The second derivative from the differences of window means alone: a
  // difference of the edges' rates would carry their noise, amplified.
  d.accel_c_per_s2 = differentiate(data.time_s, d.rate_c_per_s, data.run, mode, span_s);
  take_edge_rates(d.rate_c_per_s, data.temp_rate_c_per_s, data.temp_rate_se, mode);
  if (sensor_tau_s > 0.0) {
    for (std::size_t p = 0; p < d.temp_c.size(); ++p) {
      d.temp_c[p] += sensor_tau_s * d.rate_c_per_s[p];
      d.rate_c_per_s[p] += sensor_tau_s * d.accel_c_per_s2[p];
    }
    if (!d.temp2_c.empty()) {
      std::vector<double> rate2 = differentiate(data.time_s, data.temp2_c, data.run, mode, span_s);
      take_edge_rates(rate2, data.temp2_rate_c_per_s, data.temp2_rate_se, mode);
      for (std::size_t p = 0; p < d.temp2_c.size(); ++p) d.temp2_c[p] += sensor_tau_s * rate2[p];
    }
  }
  for (const auto& [name, values] : data.extra) {
    d.extra[name] = values;
    d.extra_rate[name] = differentiate(data.time_s, values, data.run, mode, span_s);
    if (const auto edges = data.extra_rate.find(name); edges != data.extra_rate.end())
      take_edge_rates(d.extra_rate[name], edges->second, data.extra_rate_se.at(name), mode);
  }
  return d;
}

}  // namespace gyrotherm::fit
