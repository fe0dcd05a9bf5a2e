#pragma once
// Removing counting glitches from the raw gyro samples: Hampel's test
// (fit/data/hampel.h) on a centred window in time, with a noise scale that
// survives quantisation.
//
// Every sample k valid on entry is judged against the valid samples j with
// |t_j − t_k| ≤ W/2 (W = window_s; the window is cut short at the ends of the
// record and at gaps). A pulse-counting gyro's output is quantised, so most
// samples of a window can be equal and the local MAD 0; the floor keeps the
// threshold at the noise:
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
// median tolerates while glitches are fewer than half of a window. Samples
// already invalid on entry are ignored (neither judged nor used).

#include <cstddef>
#include <vector>

#include "fit/data/hampel.h"
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
