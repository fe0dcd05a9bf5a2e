#pragma once
// The figures of `gyrotherm diagnose --plots DIR` (PNG, gnuplot):
//   bias_time.png        measured and modelled window means with the temperature
//   residual_segments.png  the residual against time, segments shaded by kind,
//                        the worst three marked
//   residual_vs.png      the residual against temperature and against dT/dt
//   before_after.png     the residual without and with the added effect (--add)
//   allan.png            Allan deviation of the raw and compensated output with
//                        68 % bands, and the noise floor at the averaging time
//                        (needs the samples: left out when `measurement` is
//                        empty, as for a log prepared in one pass)
// The plots against time break their lines at the record's gaps.

#include <string>
#include <vector>

#include "studies/diagnose/diagnosis.h"

namespace gyrotherm::studies {

void write_diagnosis_plots(const std::string& dir, const fit::Measurement& measurement,
                           const fit::PreparedData& data, const Diagnosis& d,
                           const Diagnosis* before);

// The windows that follow a gap in the record, where a line must not join
// them to the one before: more than 1.75 times the usual spacing after it
// (the window, or with bursts the median spacing of the bursts): a window or
// a burst missing, not a dropout of a few samples (with the partial window
// it may cost, at most 1.5 times).
std::vector<std::size_t> windows_after_gaps(const fit::PreparedData& data);

}  // namespace gyrotherm::studies
