#pragma once
// The noise of a ring-laser gyro's pulse-counted output, and of temperature
// readings.
//
// Every sample interval Δt (s) the gyro outputs the mean rate over the interval
// (°/h), built from the noise-free bias B (°/h) and five noise terms, each with
// its own generator (sim/util/random.h):
//
//   ARW, angle random walk N (°/√h): white rate noise w_k ~ N(0, 1),
//       n_k = a(T) · 60 N / √Δt · w_k,   a(T) = 1 + k_T (T − T_ref)²,
//       so that the Allan deviation is σ(τ) = a N / √τ_h (τ_h = τ/3600 s, σ in °/h).
//   Bias instability (flicker floor): a sum of M first-order Gauss–Markov
//       processes with correlation times τ_i log-spaced in [τ_min, τ_max] and a
//       common variance s², each discretised exactly and started stationary:
//         x_i ← φ_i x_i + s √(1 − φ_i²) w,   φ_i = exp(−Δt/τ_i).
//       s² is chosen so that max_τ √(Σ_i σ²_GM(s², τ_i, τ)) = bias_instability_dph,
//       the maximum taken over τ ≥ Δt on a fine log grid.
//   RRW, rate random walk K (°/h/√h): r_k = r_{k−1} + K √(Δt/3600) w_k, r_0 = 0,
//       σ(τ) = K √(τ_h/3).
//   Quantisation: a rate of 1 °/h held for 1 s turns the block by 1″. The true
//       angle θ (arcsec) of B + ARW + flicker + RRW is accumulated from a random
//       initial phase in [0, q); the counter registers p_k = ⌊θ_k / q⌋ pulses and
//       the output is (p_k − p_{k−1}) q / Δt. The quantisation error is a
//       bounded phase, not a walk: the mean of any window of W samples differs
//       from the mean of the unquantised rate by less than q / (W Δt). q = 0
//       turns it off.
//   Glitches: counting outliers at the times of a Poisson process of rate λ
//       (1/h); each adds ±g (random sign, °/h) to the output of the sample
//       interval it falls in, after quantisation.
//
// The Allan variance of one Gauss–Markov process of variance s² and correlation
// time T, with x = τ/T, is
//
//   σ²_GM(τ) = s² (2x − 3 + 4e^{−x} − e^{−2x}) / x²
//            → 2 s² x / 3 (τ ≪ T, random-walk-like),   → 2 s² / x (τ ≫ T, white-like).
//
// The simulation holds x_i constant over each sample, so at τ = mΔt its Allan
// variance exceeds σ²_GM by a relative O(1/(2m²)) + O((Δt/T)²): 50 % at m = 1,
// under 1 % for m ≥ 10 with T ≥ 10 Δt. For τ ≥ 10 Δt the analytic form is the
// right reference.
//
// A component whose parameter is 0 draws nothing, and the same seed gives
// bit-identical output.
//
// References: IEEE Std 952-1997, Annex B (gyro noise terms) and Annex C (Allan
// variance; Gauss–Markov correlated noise, C.1.6); N. El-Sheimy, H. Hou, X. Niu,
// "Analysis and modeling of inertial sensors using Allan variance", IEEE Trans.
// Instrum. Meas. 57 (2008); J. A. Barnes, "The generation and recognition of
// flicker noise", NBS Rep. 9284 (1966) — flicker as a sum of relaxation processes.

#include <cstdint>
#include <vector>

#include "sim/gyro_config.h"
#include "sim/util/random.h"

namespace gyrotherm::sim {

// Allan variance of a first-order Gauss–Markov process with the given variance
// (units²) and correlation time (s) at averaging time tau_s (s), in units².
double gauss_markov_allan_variance(double variance, double correlation_time_s, double tau_s);

class GyroNoise {
 public:
  // config: noise parameters (validated elsewhere); sample_interval_s: Δt > 0;
  // seed: the run's seed (each component derives its own stream from it).
  GyroNoise(const NoiseConfig& config, double sample_interval_s, std::uint64_t seed);

  // The pulse-counted output rate (°/h) for the next sample interval, given the
  // true noise-free bias (°/h) and the true gyro temperature (°C).
  double sample(double true_rate_dph, double temp_c);

  // Draws now the Gaussian variates of the next `samples` calls of sample()
  // (ARW, flicker, RRW: each from its own stream, in the order sample() would
  // draw them), which then takes them from here: the outputs are bit-identical.
  // None of them depends on the inputs, so a second thread can draw them while
  // the thermal network is integrated (Simulator::run).
  void draw_ahead(std::size_t samples);

  // The Gauss–Markov correlation times τ_i (s) and their common variance s²
  // ((°/h)²) of the flicker part; empty and 0 when bias instability is off.
  const std::vector<double>& flicker_correlation_times_s() const { return flicker_tau_s_; }
  double flicker_variance_dph2() const { return flicker_variance_dph2_; }
  // Whole pulses counted so far, ⌊θ/q⌋ (0 when quantisation is off).
  std::int64_t pulse_count() const { return pulses_; }

 private:
  NoiseConfig config_;
  double dt_s_;

  Rng arw_rng_;
  Rng flicker_rng_;
  Rng rrw_rng_;
  Rng quantizer_rng_;
  Rng glitch_rng_;

  double arw_std_dph_ = 0.0;  // per-sample std at T_ref

  std::vector<double> flicker_tau_s_;
  double flicker_variance_dph2_ = 0.0;
  std::vector<double> flicker_phi_;             // e^{−Δt/τ_i}
  std::vector<double> flicker_innovation_dph_;  // s √(1 − φ_i²)
  std::vector<double> flicker_state_dph_;       // x_i

  double rrw_step_dph_ = 0.0;  // K √(Δt/3600)
  double rrw_state_dph_ = 0.0;

  double phase_arcsec_ = 0.0;  // θ mod q, in [0, q)
  std::int64_t pulses_ = 0;    // ⌊θ / q⌋ since the start

  double glitch_rate_per_s_ = 0.0;
  double next_glitch_s_ = 0.0;  // time of the next glitch since the start
  std::uint64_t samples_ = 0;   // sample intervals completed

  // draw_ahead's variates, per sample; ahead_next_ is the next sample's index.
  std::vector<double> ahead_arw_, ahead_flicker_, ahead_rrw_;
  std::size_t ahead_samples_ = 0, ahead_next_ = 0;
};

// A temperature reading: white noise of std noise_c (°C), then rounding to the
// nearest multiple of resolution_c (°C); either may be 0 (off). Its generator
// is make_rng(seed, stream), with stream = streams::reading_base + sensor index.
class ReadingNoise {
 public:
  ReadingNoise(double noise_c, double resolution_c, std::uint64_t seed, std::uint64_t stream);

  double read(double true_c);
  // As GyroNoise::draw_ahead: the variates of the next `samples` reads.
  void draw_ahead(std::size_t samples);

 private:
  double noise_c_;
  double resolution_c_;
  Rng rng_;
  std::vector<double> ahead_;
  std::size_t ahead_next_ = 0;
};

}  // namespace gyrotherm::sim
