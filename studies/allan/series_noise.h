#pragma once
// The noise model of a gyro series for `allan` (fit/model/noise_model.h): the
// same REML identification `fit` runs on its residual, here on the series
// itself (intercept only), with windows of consecutive samples inside the
// gap-free runs. `allan` uses it where the lag-1 autocorrelation has too few
// block averages to name the noise type (long τ), and reports it in --json.

#include <optional>
#include <span>

#include "fit/model/noise_model.h"

namespace gyrotherm::studies {

// nullopt when the series has too few windows (fewer than 16) or the
// identification finds nothing it can trust.
std::optional<fit::NoiseModel> identify_series_noise(std::span<const double> time_s,
                                                     std::span<const double> rate_dph, double tau0_s);

}  // namespace gyrotherm::studies
