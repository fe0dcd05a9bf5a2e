#pragma once
// The noise model of a gyro series for `allan` (fit/model/noise_model.h): the
// same REML identification `fit` runs on its residual, here on the series
// itself (intercept only), with windows of consecutive samples inside the
// gap-free runs. `allan` uses it where the lag-1 autocorrelation has too few
// block averages to name the noise type (long τ), and reports it in --json.

#include <optional>
#include <span>

#include "fit/model/noise_model.h"
#include "studies/allan/noise_coefficients.h"

namespace gyrotherm::studies {

// nullopt when the series has too few windows (fewer than 16) or the
// identification finds nothing it can trust.
std::optional<fit::NoiseModel> identify_series_noise(std::span<const double> time_s,
                                                     std::span<const double> rate_dph, double tau0_s);

// The series' one bias-instability figure, from the curve's reading `b`
// (read_noise_coefficients) and the series' noise model: a flat part of the
// curve is only called bias instability where the noise model finds slow
// noise that accounts for it (the model's Allan deviation at the reading's
// τ reaches its interval), not what a fit's model leaves on a compensated
// series (a leftover cycle's hump lies above the noise) or a drift on its
// way up. Where the curve has a flat part and the noise model
//   * accounts for it with a Gauss–Markov process, or with flicker while the
//     flat part is a plateau (past it the curve falls below it beyond its
//     interval, as a Gauss–Markov bias does and a flicker floor does not):
//     the curve's reading stands (curve_flat), as IEEE 952 reads a
//     correlated bias (the series' model, on windows of n/512 samples, often
//     reads a Gauss–Markov process of a few windows' correlation time as
//     white noise and flicker: the curve reads its plateau better);
//   * identifies flicker otherwise: B is the model's flicker floor (method
//     noise_model; REML separates the white noise, which still adds to the
//     curve at the flat part's τ), its interval at the curve's confidence;
//   * identifies neither: a bound (the flat part's 95 % upper value).
// Without a flat part the curve's bound stands: the model's own bound on B
// holds only if its structure does (it reads a Gauss–Markov plateau as
// flicker below it), the curve's whatever the noise. Returns what supports
// the figure.
enum class BiasSupport {
  plateau,          // the curve falls past its flat part, the model's flicker accounts for it
  gauss_markov,     // the noise model's Gauss–Markov process accounts for it
  flicker,          // the noise model identifies flicker (B from the model)
  not_in_model,     // a flat part the model does not support: a bound
  no_model,         // a flat part, no noise model (too few windows): a bound
  no_flat_part,     // the curve has none: its bound
  beyond_record,    // the curve still falls at its longest usable τ: a flat part, if any, lies beyond the record
  too_few_taus,     // fewer than 3 τ with 8 clusters: the curve cannot tell
};
// "plateau", "gauss_markov", "flicker", "not_in_model", "no_model", "no_flat_part", "beyond_record", "too_few_taus"
const char* bias_support_name(BiasSupport s);
BiasSupport settle_bias_instability(NoiseCoefficient& b, const AllanCurve& curve,
                                    const std::optional<fit::NoiseModel>& noise);

}  // namespace gyrotherm::studies
