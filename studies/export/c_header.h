#pragma once
// A saved fit as a self-contained C99 header (`gyrotherm export --format c`):
// the real-time compensator of fit/causal_compensator.h (what `compensate
// --causal` runs), transcribed operation by operation so that, fed the same
// samples, it gives the same bias to rounding.
//
//   typedef struct { … } P_state;          all state, fixed size
//   void   P_init(P_state *s);
//   double P_update(P_state *s, double time_s, double temp_c, double temp2_c);
//   double P_update_gyro(P_state *s, double time_s, double temp_c, double temp2_c,
//                        double gyro_dph);
//
// P_update returns the model's bias (°/h) for the sample; it does not see the
// gyro output, so it applies no glitch rule. P_update_gyro also takes the
// gyro output (°/h) and applies the fit's glitch rule (a rejected sample
// enters no window), as compensate --causal does for a fit made with it.
// Time in seconds, temperatures in °C (convert a logger's units first);
// temp2_c is ignored by models without grad (pass 0). Only <math.h>,
// <stddef.h> and <stdint.h>; no allocation, no I/O; static functions.
//
// The glitch rule keeps the samples of its trailing window in a fixed buffer
// sized for twice the fit's sample rate; a log faster than that drops the
// oldest samples of the window (the C++ compensator keeps them all).
// A model with a log column term (NAME, d(NAME)) cannot be exported: the
// interface has no such input.

#include <string>

#include "fit/causal_compensator.h"
#include "studies/export/exporter.h"

namespace gyrotherm::studies {

// Throws InputError when the prefix is not a C identifier or a term has no C
// form.
std::string c_header(const fit::SavedFit& fit, const fit::CausalSettings& settings, const std::string& prefix,
                     const ExportHeader& header);

}  // namespace gyrotherm::studies
