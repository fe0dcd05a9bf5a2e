#pragma once
// The window mean of a quantity's time derivative, from its samples at the
// window's edges (fit/data/averaging.h).
//
// Over a window whose valid samples run from t_a to t_b, Δ apart, the mean of
// dx/dt at the samples is, to the sampling's own accuracy,
//
//     ẋ_w = (x(t_b + Δ/2) − x(t_a − Δ/2)) / (t_b − t_a + Δ),
//
// exactly what the window mean of the gyro output sees of a rate effect. The
// edge values come from the least-squares line through the first (last) k
// samples, extrapolated half a sample outward: unbiased where x is locally
// linear, and k samples average the sensor's noise and quantisation. A
// difference of neighbouring window means, the rate at the window's centre
// smoothed over two windows, is biased wherever the rate changes within that
// span (a ramp's start and end), and the bias lands on the rate's
// coefficient (issue: dT read 0.35–0.40 % high on cycles with 1–5 °C/min
// ramps).
//
// Its noise: each edge's value is an extrapolation from k samples, so a
// sensor's noise and resolution (0.003 °C, 0.01 °C steps at 1 Hz: ±5e-5 °C/s
// over 100 s) reach the rate, while a difference of window means averages
// them away. Where the two agree within three times the edges' standard error
// (standard_error(): the sample noise from the window's second differences,
// Σ(x_{i+1} − 2x_i + x_{i−1})²/6n, which a trend does not inflate and a
// sensor's steps do enter), the smooth part of a
// record, the difference of means is kept (derivatives.h); where they do
// not, at a ramp's start or end, the edges' rate is taken.

#include <cstddef>
#include <vector>

namespace gyrotherm::fit {

class EdgeRate {
 public:
  // k ≥ 2 samples for each edge's line; sample_interval_s is Δ.
  EdgeRate(std::size_t k, double sample_interval_s);
  // The samples of one window, in time order (times relative to anything fixed).
  void add(double time_s, double value);
  // ẋ_w; NaN with fewer than 2k samples (the edges' lines would share samples).
  double rate() const;
  // Its standard error from the samples' noise; NaN as rate().
  double standard_error() const;
  void reset();

  // k for a window of `window_s`: 10 % of its samples, at least 3 and at most 64.
  static std::size_t samples_for(double window_s, double sample_interval_s);

 private:
  std::size_t k_;
  double interval_s_;
  std::vector<double> first_t_, first_x_, last_t_, last_x_;  // last_*: a ring of the latest k
  std::size_t count_ = 0;
  double before_ = 0, latest_ = 0, second_differences_ = 0;  // Σ (x_{i+1} − 2x_i + x_{i−1})²
};

}  // namespace gyrotherm::fit
