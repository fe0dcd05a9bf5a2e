#pragma once
// What a gyro file (scenarios/gyro*.toml) describes: the true bias model, its
// effects' parameters, and the noise of the 1 Hz output.
//
//   B(t) = b0 + Σ_k c_k·r_k(t; θ_k)                                 [°/h]
//
// over the effects of the registry (sim/effects/effect.h): the paper's
// b1·T + b2·T² + b3·dT/dt from the [truth] table, the hidden effects from
// [hidden]. T is the true temperature at the sensor location (the anode side
// of the block, °C) and dT/dt is in °C/s. The output adds noise (sim/noise.h).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "sim/channel.h"
#include "sim/effects/effect.h"

namespace gyrotherm::sim {

struct NoiseConfig {
  double arw_deg_per_sqrt_h = 3e-4;        // angle random walk N: Allan σ(τ) = N/√τ
  double bias_instability_dph = 1e-3;      // flicker floor of the Allan deviation
  double flicker_tau_min_s = 10.0;         // shortest Gauss–Markov correlation time
  double flicker_tau_max_s = 20000.0;      // longest Gauss–Markov correlation time
  int flicker_processes = 6;               // log-spaced Gauss–Markov processes in the sum
  double rrw_dph_per_sqrt_h = 0.0;         // rate random walk K: Allan σ(τ) = K·√(τ/3)
  double quantization_arcsec = 0.05;       // angle per counted pulse (0 = off)
  double glitch_rate_per_h = 0.2;          // counting glitches (outliers), mean rate
  double glitch_size_dph = 2.0;            // glitch amplitude (random sign)
  double arw_temp_ref_c = 20.0;            // ARW is smallest at this temperature ...
  double arw_temp_coeff_per_c2 = 1e-4;     // ... and scales by 1 + k·(T − T_ref)²
};

struct GyroConfig {
  double b0_dph = -7.07712;  // constant bias incl. Earth rate on the axis
  // The true coefficient c_k of each effect by its term name; absent or 0 =
  // off. Defaults: the paper's b1 (°/h per °C), b2 (°/h per °C²) and b3
  // (°/h per °C/s).
  std::map<std::string, double> coefficient = {{"T", -3.05e-4}, {"T^2", 1.06e-6}, {"dT", 1.81}};
  // θ_k of an effect with a nonlinear parameter, by term name; absent: the
  // effect's simulator_default.
  std::map<std::string, double> parameter;
  NoiseConfig noise;
  // The channels beside the gyro's (sim/channel.h), in the file's order.
  std::vector<ChannelConfig> channels;

  // c_k (0 when off) and θ_k of an effect.
  double coefficient_of(const effects::Effect& effect) const;
  double parameter_of(const effects::Effect& effect) const;
};

// The true coefficients by term name, the intercept b0 under "1", every
// effect that is on (c_k ≠ 0): what the truth JSON records and what fits and
// campaigns are scored against. The one place they are derived.
std::map<std::string, double> true_coefficients(const GyroConfig& gyro);

}  // namespace gyrotherm::sim
