#pragma once
// Overlapping Allan deviation of a rate series.
//
// Rates y_0 … y_{n−1} (any unit, here °/h) are sampled every Δt. With the
// accumulated angle (phase) x_k = Δt Σ_{i<k} y_i, k = 0 … n, the overlapping
// Allan variance at τ = mΔt is
//
//   σ²(τ) = 1 / (2 τ² (n − 2m + 1)) · Σ_{j=0}^{n−2m} (x_{j+2m} − 2x_{j+m} + x_j)²,
//
// i.e. half the mean square difference of adjacent τ-averages, taken at every
// start sample. Each τ costs O(n) once the cumulative sum x is built. A τ needs
// at least 2 clusters (⌊n/m⌋ ≥ 2); requested τ are rounded to the nearest whole
// m ≥ 1, and τ that round to m = 0, leave fewer than 2 clusters, or repeat an
// m already computed are dropped.
//
// The 68.27 % (±1σ) confidence band uses the χ² distribution with the
// equivalent degrees of freedom of the overlapping estimator for white rate
// noise (white FM; for a gyro, angle random walk), N = n + 1 phase points:
//
//   edf = (3(N − 1)/(2m) − 2(N − 2)/N) · 4m² / (4m² + 5),
//   σ_lower = σ √(edf / χ²_{edf}(0.8413)),   σ_upper = σ √(edf / χ²_{edf}(0.1587)).
//
// For other noise types (flicker, random walk) the true band is wider at long τ.
//
// References: IEEE Std 952-1997, Annex C; W. J. Riley, "Handbook of Frequency
// Stability Analysis", NIST SP 1065 (2008), §5.2.4 and Table 5 (edf);
// D. A. Howe, D. W. Allan, J. A. Barnes, "Properties of signal sources and
// measurement methods", Proc. 35th Freq. Control Symp. (1981).

#include <cstddef>
#include <span>
#include <vector>

namespace gyrotherm::sim {

struct AllanPoint {
  double tau_s = 0.0;      // averaging time mΔt (s)
  double deviation = 0.0;  // overlapping Allan deviation, in the unit of the rates
  double lower = 0.0;      // 68 % confidence band (white-noise edf)
  double upper = 0.0;
  std::size_t clusters = 0;  // ⌊n/m⌋, the number of non-overlapping τ-clusters
};

// Overlapping Allan deviation of a rate series sampled every dt_s (s) at the
// requested tau_s (s), in the order requested, after the rounding and dropping
// described above.
std::vector<AllanPoint> allan_deviation(std::span<const double> rate, double dt_s,
                                        std::span<const double> tau_s);

// per_decade log-spaced τ from dt_s to (samples · dt_s)/10, rounded to whole
// multiples of dt_s without repeats, increasing. Empty when samples < 10.
std::vector<double> octave_taus(std::size_t samples, double dt_s, int per_decade = 5);

}  // namespace gyrotherm::sim
