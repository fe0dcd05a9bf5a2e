#pragma once
// The overlapping Allan deviation of a gyro's output with confidence
// intervals and the noise type at each τ (`gyrotherm allan`).
//
// Rates y (°/h) sampled every τ0; the record may have gaps and bursts. It is
// cut into gap-free runs (a gap: a time step above 1.5 τ0, τ0 the median
// step). In each run the angle x_k = τ0 Σ_{i<k} y_i, and at τ = mτ0
//
//   σ²(τ) = Σ_runs Σ_j (x_{j+2m} − 2x_{j+m} + x_j)² / (2τ² · #terms),
//
// the overlapping estimator (IEEE Std 952 Annex C; NIST SP 1065 §5.2.4) over
// every start j whose clusters lie inside one run: a cluster that would span a
// gap is not used, and the count of those left out is reported.
//
// Noise type. At each τ the power-law exponent α of the rate's spectrum
// S_y(f) ∝ f^α is identified by the lag-1 autocorrelation method (Riley &
// Greenhall 2004): the rates averaged over non-overlapping m-blocks (within
// runs) are differenced d times until δ = r1/(1 + r1) < 0.25 (d ≤ 2), and
// α = −2(δ + d), rounded. It needs 100 block averages (Riley's 30 lets r1
// stray by ±0.18: one white point in six was called another type). At longer τ the type is
// the one of the record's noise model (series_noise.h: white, flicker,
// Gauss–Markov, random walk identified by REML on the whole record): α =
// −μ − 1 rounded, μ the model's local log-log slope of σ²(τ); without a model
// (too short a record), μ is the least-squares slope of the curve over the
// τ within two octaves and the neighbours (at least three points; with
// fewer, white rate noise is assumed), never one pair of points. For a gyro: α = 2
// quantisation (white angle noise), 1 flicker angle noise, 0 angle random
// walk (white rate noise), −1 bias instability (flicker rate), −2 rate random
// walk.
//
// Confidence intervals. The estimate is χ²-distributed with the equivalent
// degrees of freedom of the overlapping estimator for that noise type by
// Greenhall's algorithm (greenhall_edf.h), summed over runs (runs are
// independent), and the interval at confidence c is
// σ·√(edf/χ²_edf((1 ± c)/2)) (Boost.Math).
//
// References: W. J. Riley, "Handbook of Frequency Stability Analysis", NIST
// SP 1065 (2008), §5.2.4, §5.6; C. A. Greenhall, W. J. Riley, "Uncertainty
// of stability variances based on finite differences", 35th PTTI (2003); W. J. Riley, C. A.
// Greenhall, "Power law noise identification using the lag 1
// autocorrelation", Proc. 18th EFTF (2004); IEEE Std 952-1997, Annex C.

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace gyrotherm::studies {

enum class TauSpacing { octave, decade, all };

struct AllanOptions {
  TauSpacing spacing = TauSpacing::octave;
  double confidence = 0.6827;  // of the intervals (±1σ of a normal)
  // The longest τ as a share of the record's span (the default: a
  // quarter; a τ also needs one gap-free stretch of 2τ).
  double longest_share = 0.25;
  // The longest τ asked for (s); 0: the default above. A τ beyond what the
  // record can give (one gap-free stretch of 2τ) is refused.
  double tau_max_s = 0.0;
  // The record's noise model as an Allan variance ((°/h)² at τ in s), for the
  // noise type where block averages are too few; empty: the curve's slope.
  std::function<double(double)> model_avar;
};

struct AllanRow {
  double tau_s = 0.0;
  std::size_t m = 0;           // τ / τ0
  double adev_dph = 0.0;
  double lo_dph = 0.0, hi_dph = 0.0;
  double edf = 0.0;
  int alpha = 0;               // the noise type's spectral exponent (above)
  bool alpha_from_acf = true;     // false: from the noise model, or the slope
  bool alpha_from_model = false;  // from the noise model
  std::size_t terms = 0;       // second differences used
  std::size_t gap_terms = 0;   // left out because their clusters would span a gap
};

struct AllanCurve {
  std::string name;            // "raw", "compensated", ...
  double tau0_s = 0.0;         // the sample interval (median step)
  std::size_t samples = 0, runs = 0, gaps = 0;
  double span_s = 0.0;         // first to last sample
  double longest_run_s = 0.0;
  bool limited_by_runs = false;  // the longest τ is set by the longest gap-free run, not the record's span
  double confidence = 0.6827;
  std::vector<AllanRow> rows;  // increasing τ
};

// Throws InputError when the record cannot give one τ (no gap-free run of 2
// samples), when the confidence is outside (0, 1), or when `all` τ would take
// too long. `name` names the series in messages.
AllanCurve allan_curve(std::span<const double> time_s, std::span<const double> rate_dph,
                       const AllanOptions& options, std::string name);

// The noise type's gyro name: "quantization", "flicker_angle",
// "angle_random_walk", "bias_instability", "rate_random_walk".
std::string noise_type_name(int alpha);

// The least-squares slope of ln σ against ln τ at row i, over the rows
// within `octaves` either side and its two neighbours; NaN with fewer than
// three points.
double loglog_slope(const std::vector<AllanRow>& rows, std::size_t i, double octaves);

// The overlapping Allan deviation of one gap-free series at averaging factor
// m (no intervals; NaN when the series is shorter than 2m).
double overlapping_adev(std::span<const double> rate, std::size_t m);

}  // namespace gyrotherm::studies
