#include "studies/allan/noise_coefficients.h"

#include <cmath>
#include <functional>

#include <boost/math/distributions/chi_squared.hpp>
#include <fmt/format.h>

namespace gyrotherm::studies {
namespace {

// The local log-log slope of σ(τ) at row i (to both neighbours, or the one).
double local_slope(const AllanCurve& c, std::size_t i) {
  const std::size_t a = i > 0 ? i - 1 : i, b = i + 1 < c.rows.size() ? i + 1 : i;
  if (a == b || c.rows[a].adev_dph <= 0.0 || c.rows[b].adev_dph <= 0.0) return std::nan("");
  return std::log(c.rows[b].adev_dph / c.rows[a].adev_dph) / std::log(c.rows[b].tau_s / c.rows[a].tau_s);
}

// The coefficient of a slope region (τ of the term's noise type where the
// curve's local slope is the term's, within ±0.1: next to another region the
// two mix, and a reading there would carry the other term too), read at the
// region's τ with the most degrees of freedom, scaled by `scale(τ)`.
NoiseCoefficient slope_region(const AllanCurve& c, int alpha, double slope,
                              const std::function<double(double)>& scale, const std::string& what) {
  NoiseCoefficient k;
  const AllanRow* best = nullptr;
  // The region within ±0.1; read where the slope is within ±0.05 if any τ is.
  for (const double tolerance : {0.05, 0.1}) {
    for (std::size_t i = 0; i < c.rows.size(); ++i) {
      const AllanRow& r = c.rows[i];
      const double off = std::abs(local_slope(c, i) - slope);
      if (r.alpha != alpha || !(off <= 0.1)) continue;
      if (k.tau_from_s == 0.0) k.tau_from_s = r.tau_s;
      k.tau_to_s = std::max(k.tau_to_s, r.tau_s);
      if (off <= tolerance && (!best || r.edf > best->edf)) best = &r;
    }
    if (best) break;
  }
  if (!best) {
    k.note = c.rows.empty() ? "no τ" : fmt::format("not shown: no τ from {:.3g} to {:.3g} s where {} shows alone",
                                                   c.rows.front().tau_s, c.rows.back().tau_s, what);
    return k;
  }
  k.shown = true;
  k.tau_read_s = best->tau_s;
  const double s = scale(best->tau_s);
  k.value = best->adev_dph * s;
  k.lo = best->lo_dph * s;
  k.hi = best->hi_dph * s;
  k.note = fmt::format("{} region τ = {:.3g}–{:.3g} s, read at τ = {:.3g} s", what, k.tau_from_s, k.tau_to_s,
                       k.tau_read_s);
  return k;
}

NoiseCoefficient bias_instability(const AllanCurve& c) {
  NoiseCoefficient k;
  const std::size_t n = c.rows.size();
  if (n < 3) {
    k.note = "not shown: fewer than 3 τ";
    return k;
  }
  std::size_t lowest = 0, highest = 0;
  for (std::size_t i = 1; i < n; ++i) {
    if (c.rows[i].adev_dph < c.rows[lowest].adev_dph) lowest = i;
    if (c.rows[i].adev_dph > c.rows[highest].adev_dph) highest = i;
  }
  std::size_t at = n;
  std::string shape;
  // Still falling at the longest τ, but flat there (the last step's slope
  // above −0.2, where white rate noise alone falls at −½): the flat part has
  // begun, and its rise is beyond the record.
  const double last_slope = std::log(c.rows[n - 1].adev_dph / c.rows[n - 2].adev_dph) /
                            std::log(c.rows[n - 1].tau_s / c.rows[n - 2].tau_s);
  // And significantly so: even the 95 % lower bound of the last τ lies above
  // the −½ line from two τ before (white noise with few clusters often
  // flattens by chance over the last step).
  const AllanRow& last = c.rows[n - 1];
  const AllanRow& before = c.rows[n - 3];
  const double lo95 =
      last.adev_dph * std::sqrt(last.edf / boost::math::quantile(boost::math::chi_squared(last.edf), 0.975));
  const double white_line = before.adev_dph * std::sqrt(before.tau_s / last.tau_s);
  if (lowest + 1 == n && last_slope > -0.2 && lo95 > white_line) {
    at = lowest;
    shape = "the flat end of the curve (its rise is beyond the record, so B may be a little lower)";
  } else if (lowest > 0 && lowest + 1 < n) {
    at = lowest;
    shape = "the curve's minimum";
  } else if (highest > 0 && highest + 1 < n) {
    at = highest;
    shape = "the top of the curve's hump (a correlated, Gauss–Markov-like bias)";
  }
  if (at == n) {
    k.note = lowest + 1 == n ? fmt::format("not shown: the curve still falls at the longest τ ({:.3g} s); the "
                                           "record is too short to show the flat part",
                                           c.rows.back().tau_s)
                             : fmt::format("not shown: the curve rises from the shortest τ ({:.3g} s)",
                                           c.rows.front().tau_s);
    return k;
  }
  const AllanRow& r = c.rows[at];
  // The flat part: the τ around the extremum whose deviation lies inside its interval.
  std::size_t from = at, to = at;
  while (from > 0 && c.rows[from - 1].adev_dph >= r.lo_dph && c.rows[from - 1].adev_dph <= r.hi_dph) --from;
  while (to + 1 < n && c.rows[to + 1].adev_dph >= r.lo_dph && c.rows[to + 1].adev_dph <= r.hi_dph) ++to;
  k.shown = true;
  k.tau_read_s = r.tau_s;
  k.tau_from_s = c.rows[from].tau_s;
  k.tau_to_s = c.rows[to].tau_s;
  k.value = r.adev_dph / kFlickerFloor;
  k.lo = r.lo_dph / kFlickerFloor;
  k.hi = r.hi_dph / kFlickerFloor;
  k.note = fmt::format("{} at τ = {:.3g} s (flat within its interval from {:.3g} to {:.3g} s), σ/0.664", shape,
                       r.tau_s, k.tau_from_s, k.tau_to_s);
  if (r.alpha != -1)
    k.note += fmt::format("; the noise there identifies as {}, so flicker is not alone and this bounds B from above",
                          noise_type_name(r.alpha));
  return k;
}

}  // namespace

NoiseCoefficients read_noise_coefficients(const AllanCurve& c) {
  NoiseCoefficients k;
  k.arw_dpsh = slope_region(c, 0, -0.5, [](double tau) { return std::sqrt(tau / 3600.0); },
                            "angle random walk (−½ slope)");
  k.rrw_dph_per_sqrt_h = slope_region(c, -2, 0.5, [](double tau) { return std::sqrt(3.0 / (tau / 3600.0)); },
                                      "rate random walk (+½ slope)");
  k.quantization_arcsec = slope_region(c, 2, -1.0, [](double tau) { return tau / std::sqrt(3.0); },
                                       "quantisation (−1 slope)");
  k.bias_instability_dph = bias_instability(c);
  return k;
}

}  // namespace gyrotherm::studies
