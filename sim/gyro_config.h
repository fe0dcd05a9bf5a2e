#pragma once
// What a gyro file (scenarios/gyro*.toml) describes: the true bias model, the
// hidden physical effects, and the noise of the 1 Hz output.
//
//   B(t) = b0 + b1·T + b2·T² + b3·dT/dt + Σ_k c_k·r_k(t)          [°/h]
//
// T is the true temperature at the sensor location (the anode side of the
// block, °C) and dT/dt is in °C/s; r_k are the hidden-effect regressors of
// sim/hidden_effects.h. The output adds noise (sim/noise.h).

#include <cstdint>
#include <map>
#include <string>

namespace gyrotherm::sim {

struct TruthCoefficients {
  double b0_dph = -7.07712;            // constant bias incl. Earth rate on the axis
  double b1_dph_per_c = -3.05e-4;      // temperature sensitivity
  double b2_dph_per_c2 = 1.06e-6;      // curvature
  double b3_dph_per_c_per_s = 1.81;    // temperature-rate sensitivity
};

struct HiddenEffects {
  // Coefficient by term name (see sim/hidden_effects.h); absent or 0 = off.
  std::map<std::string, double> coefficient;
  double hyst_dead_band_c_per_s = 2e-4;   // |dT/dt| below this counts as neither heating nor cooling
  double warmup_time_constant_s = 1800.0; // turn-on transient exp(−t/τ)
};

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
  TruthCoefficients truth;
  HiddenEffects hidden;
  NoiseConfig noise;
};

}  // namespace gyrotherm::sim
