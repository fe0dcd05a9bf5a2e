#pragma once
// Removing counting glitches from the raw gyro samples: a Hampel filter with a
// window in time and a noise scale that survives quantisation.
//
// For every sample k still valid on entry, over the valid samples j with
// |t_j − t_k| ≤ W/2 (W = window_s; the window is cut short at the ends of the
// record and at gaps):
//
//   m_k = median_j x_j,                        the moving median,
//   s_k = max(1.4826 · median_j |x_j − m_k|,  the local MAD,
//             s_floor),                         the global floor,
//   sample k is a glitch  ⇔  |x_k − m_k| > threshold · s_k.
//
// A pulse-counting gyro's output is quantised, so most samples of a window can
// be equal and the local MAD 0; the floor keeps the threshold at the noise:
//
//   s_floor = 1.4826 · median_k |x_k − x_{k−1}| / √2     over the whole record,
//           = min { |x_k − x_{k−1}| > 0 }                if that median is 0
//
// (the first line is the MAD of white noise estimated from first differences,
// which a slow trend does not bias; the second is the quantum of the output).
// Differences below 10⁻⁹ · max|x| count as 0 (printing round-off).
//
// A centred median follows a linear trend exactly and the trend inflates the
// MAD, so no genuine sample on a temperature ramp is flagged. The test is not
// iterated: flagged samples still enter their neighbours' medians, which a
// median tolerates while glitches are fewer than half of a window. A sample
// whose window holds fewer than 3 valid samples is not judged. Samples already
// invalid on entry are ignored (neither judged nor used).
//
// Cost O(N log N) for one sort plus O(log N) per sample for the median and
// O(log w · log N) for a MAD (w = samples per window): window members are
// marked in a Fenwick tree over the samples' ranks in value, which gives the
// median by rank, and the MAD as the k-th smallest of two sorted sequences
// (distances below and above the median). The MAD is computed only where the
// floor alone cannot clear the sample, and on the samples the report's scale
// is taken over (about 0.2 s per 10⁶ samples here).
//
// References: F. R. Hampel, "The influence curve and its role in robust
// estimation", JASA 69 (1974); R. K. Pearson, "Outliers in process modeling and
// identification", IEEE Trans. Control Syst. Technol. 10(1):55-63 (2002);
// Pearson et al., "Generalized Hampel filters", EURASIP J. Adv. Signal Process.
// 2016:87.

#include <cstddef>
#include <vector>

#include "fit/data/measurement.h"

namespace gyrotherm::fit {

struct OutlierOptions {
  double window_s = 60.0;  // full width W of the moving window, s (the window is ±W/2)
  double threshold = 8.0;  // a sample is a glitch beyond threshold × noise scale
                           // from the moving median (Hampel's t; 3 is classic, 8
                           // keeps Gaussian noise of any realistic length intact)

  // Throws InputError naming the field, the value and the rule.
  void validate() const;
};

struct OutlierReport {
  std::size_t removed = 0;      // samples newly marked invalid
  std::vector<double> times_s;  // their times, increasing
  double scale_dph = 0;         // the noise scale used: the median of s_k over the
                                // judged samples (over an evenly spaced 10⁴ of them on
                                // longer records); never below floor_dph
  double floor_dph = 0;         // the global floor s_floor
};

inline constexpr double kMadToSigma = 1.4826;  // 1/Φ⁻¹(3/4): MAD of N(0, σ²) is σ/1.4826
inline constexpr double kZeroRelative = 1e-9;  // differences below this × max|x| are round-off

// s_floor of the header from the jumps |x_k − x_{k−1}| between consecutive
// samples; jumps up to zero_dph (= kZeroRelative · max|x|) count as 0.
double noise_floor_from_jumps(std::vector<double> jumps, double zero_dph);

// Marks as invalid (valid[k] = 0) every sample whose gyro value deviates from
// the moving median of a window of ±window_s/2 around it by more than
// threshold × scale (see above). `valid` has size m.size(), initialised to 1 by
// the caller; samples already 0 are left alone.
OutlierReport flag_outliers(const Measurement& m, const OutlierOptions& options,
                            std::vector<unsigned char>& valid);

}  // namespace gyrotherm::fit
