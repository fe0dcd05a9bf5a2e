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
// α = −2(δ + d), rounded. It needs 30 block averages; beyond that (long τ)
// α comes from the local log-log slope μ of σ²(τ) ∝ τ^μ, α = −μ − 1. For a
// gyro: α = 2 quantisation (white angle noise), 1 flicker angle noise,
// 0 angle random walk (white rate noise), −1 bias instability (flicker rate),
// −2 rate random walk.
//
// Confidence intervals. The estimate is χ²-distributed with the equivalent
// degrees of freedom of the overlapping estimator for that noise type, NIST
// SP 1065 Table 5 (N phase points per run, edf summed over runs since runs
// are independent):
//   α = 2:  (N + 1)(N − 2m) / (2(N − m))
//   α = 1:  exp √(ln((N − 1)/2m) · ln((2m + 1)(N − 1)/4))
//   α = 0:  (3(N − 1)/2m − 2(N − 2)/N) · 4m²/(4m² + 5)
//   α = −1: 2(N − 2)²/(2.3N − 4.9) for m = 1, 5N²/(4m(N + 3m)) for m ≥ 2
//   α = −2: (N − 2)/m · ((N − 1)² − 3m(N − 1) + 4m²)/(N − 3)²
// and the interval at confidence c is σ·√(edf/χ²_edf((1 ± c)/2)) (Boost.Math).
//
// References: W. J. Riley, "Handbook of Frequency Stability Analysis", NIST
// SP 1065 (2008), §5.2.4, §5.5.2 (Table 5), §5.6; W. J. Riley, C. A.
// Greenhall, "Power law noise identification using the lag 1
// autocorrelation", Proc. 18th EFTF (2004); IEEE Std 952-1997, Annex C.

#include <cstddef>
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
};

struct AllanRow {
  double tau_s = 0.0;
  std::size_t m = 0;           // τ / τ0
  double adev_dph = 0.0;
  double lo_dph = 0.0, hi_dph = 0.0;
  double edf = 0.0;
  int alpha = 0;               // the noise type's spectral exponent (above)
  bool alpha_from_acf = true;  // false: from the local slope
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

// The overlapping Allan deviation of one gap-free series at averaging factor
// m (no intervals; NaN when the series is shorter than 2m).
double overlapping_adev(std::span<const double> rate, std::size_t m);

}  // namespace gyrotherm::studies
