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

#include <string>

#include "studies/diagnose/diagnosis.h"

namespace gyrotherm::studies {

void write_diagnosis_plots(const std::string& dir, const fit::Measurement& measurement,
                           const fit::PreparedData& data, const Diagnosis& d,
                           const Diagnosis* before);

}  // namespace gyrotherm::studies
