#pragma once
// The state every regressor reads (sim/effects/effect.h's EffectSeries), built
// from the window means: time since the first sample, the means of temp_c
// (and temp2_c), and their first and second time derivatives. The gyro is
// taken to be switched on at the first sample (for warmup).
//
// Derivatives are taken on the averaged series within each gap-free run:
// central differences (the default; one-sided at the ends of a run), or
// backward differences for a causal, real-time compensator (0 at the first
// window of a run).

#include "fit/data/averaging.h"
#include "sim/effects/effect.h"

namespace gyrotherm::fit {

enum class DerivativeMode { central, causal };
// "central" or "causal", as the fit file and reports write it.
const char* to_string(DerivativeMode mode);

// The fit's name for the effects' state series.
using DerivedSeries = effects::EffectSeries;

DerivedSeries derive(const AveragedSeries& data, DerivativeMode mode);

}  // namespace gyrotherm::fit
