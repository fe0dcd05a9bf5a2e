#pragma once
// The gyro's noise as `gyrotherm plan` predicts with it: the window-mean
// covariance of fit/model/noise_model.h (white, a flicker bank, one
// Gauss–Markov process, rate random walk), plus the simulator's
// temperature-dependent white noise (sim/noise.h: the white noise's standard
// deviation × a(T) = 1 + k·(T − T_ref)²), and the same noise written back as
// a gyro file's [noise] table so that `gyrotherm simulate` (and plan --verify)
// draws it.
//
// Sources:
//   a gyro file (scenarios/gyro.toml): exactly the simulator's noise: white
//     q_w = (60·N)² (°/h)²·s; the flicker bank's own correlation times and
//     common variance (sim::GyroNoise); random walk q_r = K²/3600. Quantisation
//     and glitches are left out: the quantisation error of a window mean is a
//     difference of two bounded phases, which cancels along any slowly varying
//     regressor, and glitches are removed by the fitter's outlier rule.
//   a JSON with a `noise_model` object (fit --json, diagnose --json; allan
//     --json's series[].noise_model, the `compensated` series if there is one,
//     else `raw`): components arw (°/√h), bias_instability (°/h),
//     gauss_markov (°/h) with gauss_markov_tau (s), rrw (°/h/√h), each
//     {value, ...}. Flicker of floor B becomes a bank of Gauss–Markov
//     processes two per decade from kJsonFlickerMinS to kJsonFlickerMaxS
//     (wider than any plan: a 1/f spectrum has power at every period a test
//     can last) scaled so that its Allan floor is B: its common s² is the one
//     sim::GyroNoise gives such a bank at Δt = 1 s (the peak of the Allan
//     deviation over τ ≥ 1 s is B), so the bank written back to a gyro file
//     draws the same s². a(T) = 1 (k = 0).

#include <filesystem>
#include <optional>
#include <string>

#include "fit/model/noise_model.h"
#include "sim/gyro_config.h"
#include "studies/plan/plan_notes.h"

namespace gyrotherm::studies::plan {

inline constexpr double kJsonFlickerMinS = 10.0;
inline constexpr double kJsonFlickerMaxS = 1.0e6;

struct PlanNoise {
  // amplitude[], flicker_tau_s, gm_tau_s, flicker_floor_per_s (B/s, so that
  // parameters() and description() give B); present[] and identified[] set
  // for every component there (a model given, not estimated: parameters()
  // reports it with an interval of zero width, not as a bound).
  fit::NoiseModel model;
  double arw_temp_ref_c = 20.0;        // white std × (1 + k (T − T_ref)²)
  double arw_temp_coeff_per_c2 = 0.0;  // k
  std::string source;                  // "gyro file scenarios/gyro.toml", "noise_model of fit.json"
  // "white N = 2.7e-04 °/√h, flicker B = 3.0e-04 °/h (6 processes 10..20000 s)"
  std::string description() const;
  // White variance factor a(T)² at temperature T.
  double white_factor(double temp_c) const {
    const double d = temp_c - arw_temp_ref_c;
    const double a = 1.0 + arw_temp_coeff_per_c2 * d * d;
    return a * a;
  }
};

// The noise of a gyro file's [noise] at the given sample interval (s).
PlanNoise noise_of_gyro(const sim::NoiseConfig& noise, double sample_interval_s, std::string source);

// The noise_model of a JSON file (see above). Throws InputError naming the
// file and the field when it has none (or it is null), a component is not a
// non-negative number (an absent component is 0), gauss_markov > 0 comes
// without gauss_markov_tau > 0, every component is 0, or the file holds
// several channels ({"channels": […]}: which one is not ours to guess).
PlanNoise noise_of_json(const std::filesystem::path& file);

// A gyro's [noise] table that makes the simulator draw `noise` (for the gyro
// file plan writes beside its scenario): arw, rrw, the flicker bank as
// flicker_tau_min_s/max_s/processes with bias_instability_dph, quantisation
// and glitches 0 unless `base` (the gyro file's own) had them and the noise
// came from that file. A Gauss–Markov process with flicker present cannot be
// written (the gyro file has one bank): it is merged into the bank by its
// variance, and *merged says how; a Gauss–Markov process alone is a
// one-process bank.
sim::NoiseConfig noise_config_of(const PlanNoise& noise, const sim::NoiseConfig& base, bool from_gyro_file,
                                 std::optional<GaussMarkovMerged>* merged);

}  // namespace gyrotherm::studies::plan
