#include "studies/allan/series_noise.h"

#include <algorithm>
#include <cmath>

#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>

#include "sim/util/input_error.h"

namespace gyrotherm::studies {

std::optional<fit::NoiseModel> identify_series_noise(std::span<const double> time_s,
                                                     std::span<const double> rate_dph, double tau0_s) {
  const std::size_t n = time_s.size();
  if (n < 16 || !(tau0_s > 0.0)) return std::nullopt;
  // About 512 windows over the record: about eight per block mean the
  // identification aggregates (it uses at most 64 by default), each a whole
  // number of samples; the model serves the τ beyond n/100 samples, far above a window.
  const std::size_t per = std::max<std::size_t>(1, n / 512);
  fit::WindowGrid grid;
  grid.window_s = static_cast<double>(per) * tau0_s;
  std::vector<double> means;
  std::size_t start = 0;
  while (start < n) {
    std::size_t end = start + 1;  // one window: `per` samples without a gap
    while (end < n && end - start < per && time_s[end] - time_s[end - 1] <= 1.5 * tau0_s) ++end;
    if (end - start == per) {
      double t = 0.0, y = 0.0;
      for (std::size_t i = start; i < end; ++i) {
        t += time_s[i];
        y += rate_dph[i];
      }
      grid.time_s.push_back(t / static_cast<double>(per));
      grid.averaging_s.push_back(grid.window_s);
      means.push_back(y / static_cast<double>(per));
    }
    start = end;
  }
  if (means.size() < 16) return std::nullopt;
  const auto count = static_cast<Eigen::Index>(means.size());
  try {
    return fit::identify_noise(grid, Eigen::MatrixXd(count, 0), Eigen::Map<const Eigen::VectorXd>(means.data(), count));
  } catch (const FitError&) {
    return std::nullopt;
  }
}

const char* bias_support_name(BiasSupport s) {
  static constexpr const char* kNames[] = {"plateau",  "gauss_markov", "flicker",      "not_in_model",
                                           "no_model", "no_flat_part", "beyond_record", "too_few_taus"};  // the enum's order
  return kNames[static_cast<int>(s)];
}

namespace {

// The model's flicker floor B (°/h) and the τ range where flicker makes at
// least half of the model's Allan variance (else the τ where its share is
// largest), over the curve's rows.
void read_from_model(NoiseCoefficient& b, const AllanCurve& curve, const fit::NoiseModel& m) {
  fit::NoiseModel flicker_only;
  flicker_only.amplitude[fit::kFlicker] = m.amplitude[fit::kFlicker];
  flicker_only.flicker_tau_s = m.flicker_tau_s;
  double best_share = -1.0, best_tau = 0.0, from = 0.0, to = 0.0;
  for (const AllanRow& r : curve.rows) {
    const double total = m.allan_variance(r.tau_s);
    const double share = total > 0.0 ? flicker_only.allan_variance(r.tau_s) / total : 0.0;
    if (share > best_share) {
      best_share = share;
      best_tau = r.tau_s;
    }
    if (share >= 0.5) {
      if (from == 0.0) from = r.tau_s;
      to = r.tau_s;
    }
  }
  const double amplitude = m.amplitude[fit::kFlicker];
  const double value = m.flicker_floor_per_s * std::sqrt(amplitude);
  // ln B = ½ ln s²: its sd from the REML covariance of s².
  const double sd = 0.5 * std::sqrt(std::max(0.0, m.covariance(1, 1))) / amplitude;
  const double z = boost::math::quantile(boost::math::normal(), 0.5 + 0.5 * curve.confidence);
  b.shown = true;
  b.method = CoefficientMethod::noise_model;
  b.value = value;
  b.lo = value * std::exp(-z * sd);
  b.hi = value * std::exp(z * sd);
  b.upper_bound = 0.0;
  b.tau_from_s = from > 0.0 ? from : best_tau;
  b.tau_to_s = from > 0.0 ? to : best_tau;
  b.tau_read_s = best_tau;
  b.reading = Reading::noise_model;
  b.flicker_dominates = from > 0.0;
}

}  // namespace

BiasSupport settle_bias_instability(NoiseCoefficient& b, const AllanCurve& curve,
                                    const std::optional<fit::NoiseModel>& noise) {
  if (!b.shown)  // why the curve gave no flat part
    return b.reading == Reading::too_few_clusters ? BiasSupport::too_few_taus
           : b.reading == Reading::still_falling  ? BiasSupport::beyond_record
                                                  : BiasSupport::no_flat_part;
  const bool has_flicker = noise && noise->identified[fit::kFlicker] && noise->amplitude[fit::kFlicker] > 0.0 &&
                           noise->flicker_floor_per_s > 0.0;
  // The model accounts for the flat part's level: its Allan deviation there
  // reaches the reading's interval (a leftover hump of a compensation lies
  // above what the noise gives).
  const double lo_at_read = b.lo * kFlickerFloor;
  const bool accounted = noise && std::sqrt(noise->allan_variance(b.tau_read_s)) >= lo_at_read;
  if (b.plateau && has_flicker && accounted) return BiasSupport::plateau;
  if (noise && noise->identified[fit::kGaussMarkov] && noise->amplitude[fit::kGaussMarkov] > 0.0 && accounted) {
    b.gauss_markov_tau_s = noise->gm_tau_s;
    return BiasSupport::gauss_markov;
  }
  if (has_flicker) {
    read_from_model(b, curve, *noise);
    return BiasSupport::flicker;
  }
  const BiasSupport why = noise ? BiasSupport::not_in_model : BiasSupport::no_model;
  // The flat part's 95 % upper value, at the τ it was read.
  double edf = 0.0;
  for (const AllanRow& r : curve.rows)
    if (r.tau_s == b.tau_read_s) edf = r.edf;
  const double level = b.value * kFlickerFloor;
  const double upper = edf > 0.0 ? level * std::sqrt(chi2_bound(edf, 0.025)) : b.hi * kFlickerFloor;
  b.shown = false;
  b.upper_bound = upper / kFlickerFloor;
  b.reading = Reading::unexplained_flat;
  b.has_noise_model = noise.has_value();
  return why;
}

}  // namespace gyrotherm::studies
