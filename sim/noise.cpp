#include "sim/noise.h"

#include "sim/util/gauss_markov.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <boost/random/bernoulli_distribution.hpp>
#include <boost/random/exponential_distribution.hpp>
#include <boost/random/normal_distribution.hpp>
#include <boost/random/uniform_real_distribution.hpp>

namespace gyrotherm::sim {

namespace {

constexpr double kSecondsPerHour = 3600.0;
// Grid for the peak of the flicker Allan deviation: 200 points per decade put
// the grid maximum within ~1e-5 (relative) of the true one.
constexpr double kPeakGridPerDecade = 200.0;
// The peak of a Gauss–Markov Allan deviation is at τ ≈ 1.9 T, so searching up
// to 100 τ_max brackets it with room to spare.
constexpr double kPeakGridReach = 100.0;

double unit_normal(Rng& rng) {
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  return normal(rng);
}

}  // namespace

double gauss_markov_allan_variance(double variance, double correlation_time_s, double tau_s) {
  assert(variance >= 0.0 && correlation_time_s > 0.0 && tau_s > 0.0);
  return variance * gauss_markov_allan_shape(tau_s / correlation_time_s);
}

GyroNoise::GyroNoise(const NoiseConfig& config, double sample_interval_s, std::uint64_t seed)
    : config_(config),
      dt_s_(sample_interval_s),
      arw_rng_(make_rng(seed, streams::arw)),
      flicker_rng_(make_rng(seed, streams::flicker)),
      rrw_rng_(make_rng(seed, streams::rrw)),
      quantizer_rng_(make_rng(seed, streams::quantizer)),
      glitch_rng_(make_rng(seed, streams::glitch)) {
  assert(dt_s_ > 0.0);
  assert(config_.arw_deg_per_sqrt_h >= 0.0 && config_.bias_instability_dph >= 0.0 &&
         config_.rrw_dph_per_sqrt_h >= 0.0 && config_.quantization_arcsec >= 0.0 &&
         config_.glitch_rate_per_h >= 0.0);

  // ARW: σ(τ) = N/√τ_h = 60 N/√τ_s (°/h), and white noise averages as σ₁/√(τ/Δt),
  // so the per-sample std is σ₁ = 60 N/√Δt.
  arw_std_dph_ = 60.0 * config_.arw_deg_per_sqrt_h / std::sqrt(dt_s_);

  if (config_.bias_instability_dph > 0.0) {
    const int count = config_.flicker_processes;
    assert(count >= 1 && config_.flicker_tau_min_s > 0.0 &&
           config_.flicker_tau_max_s >= config_.flicker_tau_min_s);
    // 1. Correlation times log-spaced over [τ_min, τ_max] (the geometric mean
    //    of the two for a single process).
    const double log_min = std::log(config_.flicker_tau_min_s);
    const double log_max = std::log(config_.flicker_tau_max_s);
    for (int i = 0; i < count; ++i) {
      const double fraction = count == 1 ? 0.5 : static_cast<double>(i) / (count - 1);
      flicker_tau_s_.push_back(std::exp(log_min + fraction * (log_max - log_min)));
    }
    // 2. The peak of the unit-variance sum's Allan deviation over τ ≥ Δt (shorter
    //    τ cannot be observed at this sampling interval).
    const double tau_lo_s = dt_s_;
    const double tau_hi_s = std::max(kPeakGridReach * config_.flicker_tau_max_s, tau_lo_s);
    const auto steps =
        static_cast<int>(std::ceil(kPeakGridPerDecade * std::log10(tau_hi_s / tau_lo_s)));
    const double peak_avar = bank_allan_peak(flicker_tau_s_, tau_lo_s, tau_hi_s, steps);
    assert(peak_avar > 0.0);
    // 3. Scale the common variance so that the peak deviation is the bias instability.
    const double bi = config_.bias_instability_dph;
    flicker_variance_dph2_ = bi * bi / peak_avar;
    const double s = std::sqrt(flicker_variance_dph2_);
    // 4. Exact discretisation; √(1 − φ²) = √(−expm1(−2Δt/τ)) keeps digits when Δt ≪ τ.
    //    Each process starts from its stationary distribution N(0, s²).
    for (double t : flicker_tau_s_) {
      flicker_phi_.push_back(std::exp(-dt_s_ / t));
      flicker_innovation_dph_.push_back(s * std::sqrt(-std::expm1(-2.0 * dt_s_ / t)));
      flicker_state_dph_.push_back(s * unit_normal(flicker_rng_));
    }
  }

  rrw_step_dph_ = config_.rrw_dph_per_sqrt_h * std::sqrt(dt_s_ / kSecondsPerHour);

  if (config_.quantization_arcsec > 0.0) {
    boost::random::uniform_real_distribution<double> uniform(0.0, config_.quantization_arcsec);
    phase_arcsec_ = uniform(quantizer_rng_);
  }

  if (config_.glitch_rate_per_h > 0.0) {
    glitch_rate_per_s_ = config_.glitch_rate_per_h / kSecondsPerHour;
    boost::random::exponential_distribution<double> wait(glitch_rate_per_s_);
    next_glitch_s_ = wait(glitch_rng_);
  } else {
    next_glitch_s_ = std::numeric_limits<double>::infinity();
  }
}

void GyroNoise::draw_ahead(std::size_t samples) {
  assert(ahead_next_ == ahead_samples_);  // the previous ones are used up
  const std::size_t processes = flicker_state_dph_.size();
  ahead_arw_.resize(arw_std_dph_ > 0.0 ? samples : 0);
  ahead_flicker_.resize(samples * processes);
  ahead_rrw_.resize(rrw_step_dph_ > 0.0 ? samples : 0);
  for (double& z : ahead_arw_) z = unit_normal(arw_rng_);
  for (double& z : ahead_flicker_) z = unit_normal(flicker_rng_);
  for (double& z : ahead_rrw_) z = unit_normal(rrw_rng_);
  ahead_samples_ = samples;
  ahead_next_ = 0;
}

double GyroNoise::sample(double true_rate_dph, double temp_c) {
  assert(std::isfinite(true_rate_dph) && std::isfinite(temp_c));
  double rate_dph = true_rate_dph;
  const bool ahead = ahead_next_ < ahead_samples_;
  const std::size_t k = ahead_next_;

  if (arw_std_dph_ > 0.0) {
    const double dtemp_c = temp_c - config_.arw_temp_ref_c;
    const double scale = 1.0 + config_.arw_temp_coeff_per_c2 * dtemp_c * dtemp_c;
    rate_dph += scale * arw_std_dph_ * (ahead ? ahead_arw_[k] : unit_normal(arw_rng_));
  }

  const std::size_t processes = flicker_state_dph_.size();
  for (std::size_t i = 0; i < processes; ++i) {
    const double z = ahead ? ahead_flicker_[k * processes + i] : unit_normal(flicker_rng_);
    flicker_state_dph_[i] = flicker_phi_[i] * flicker_state_dph_[i] + flicker_innovation_dph_[i] * z;
    rate_dph += flicker_state_dph_[i];
  }

  if (rrw_step_dph_ > 0.0) {
    rrw_state_dph_ += rrw_step_dph_ * (ahead ? ahead_rrw_[k] : unit_normal(rrw_rng_));
    rate_dph += rrw_state_dph_;
  }
  if (ahead && ++ahead_next_ == ahead_samples_) {  // used up: free them
    ahead_arw_ = {};
    ahead_flicker_ = {};
    ahead_rrw_ = {};
  }

  double output_dph = rate_dph;
  const double q = config_.quantization_arcsec;
  if (q > 0.0) {
    // (°/h)·s = arcsec. Only θ mod q is kept as a double, so its digits do not
    // drain away as the angle grows; whole pulses go to an integer counter.
    phase_arcsec_ += rate_dph * dt_s_;
    double new_pulses = std::floor(phase_arcsec_ / q);
    phase_arcsec_ -= new_pulses * q;
    // Rounding can leave the remainder a hair outside [0, q); move one pulse.
    if (phase_arcsec_ < 0.0) {
      phase_arcsec_ += q;
      new_pulses -= 1.0;
    } else if (phase_arcsec_ >= q) {
      phase_arcsec_ -= q;
      new_pulses += 1.0;
    }
    const auto counted = static_cast<std::int64_t>(new_pulses);
    pulses_ += counted;
    output_dph = static_cast<double>(counted) * q / dt_s_;
  }

  ++samples_;
  const double interval_end_s = static_cast<double>(samples_) * dt_s_;
  if (glitch_rate_per_s_ > 0.0) {
    boost::random::exponential_distribution<double> wait(glitch_rate_per_s_);
    boost::random::bernoulli_distribution<double> positive(0.5);
    while (next_glitch_s_ < interval_end_s) {
      output_dph += positive(glitch_rng_) ? config_.glitch_size_dph : -config_.glitch_size_dph;
      next_glitch_s_ += wait(glitch_rng_);
    }
  }
  return output_dph;
}

ReadingNoise::ReadingNoise(double noise_c, double resolution_c, std::uint64_t seed,
                           std::uint64_t stream)
    : noise_c_(noise_c), resolution_c_(resolution_c), rng_(make_rng(seed, stream)) {
  assert(noise_c_ >= 0.0 && resolution_c_ >= 0.0);
}

void ReadingNoise::draw_ahead(std::size_t samples) {
  assert(ahead_next_ == ahead_.size());
  ahead_.resize(noise_c_ > 0.0 ? samples : 0);
  for (double& z : ahead_) z = unit_normal(rng_);
  ahead_next_ = 0;
}

double ReadingNoise::read(double true_c) {
  double reading_c = true_c;
  if (noise_c_ > 0.0) {
    const double z = ahead_next_ < ahead_.size() ? ahead_[ahead_next_++] : unit_normal(rng_);
    reading_c += noise_c_ * z;
  }
  if (resolution_c_ > 0.0) reading_c = resolution_c_ * std::round(reading_c / resolution_c_);
  return reading_c;
}

}  // namespace gyrotherm::sim
