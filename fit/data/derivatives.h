#pragma once
// The state every regressor reads (sim/effects/effect.h's EffectSeries), built
// from the window means: time since the first sample, the means of temp_c
// (and temp2_c), and their first and second time derivatives. The gyro is
// taken to be switched on at the first sample (for warmup).
//
// Derivatives are taken on the window means at their actual centre times:
// central differences (the default), or backward differences for a causal,
// real-time compensator. A neighbouring window is used when it belongs to the
// same gap-free run (contiguous windows, whatever their length), or across a
// gap when its centre is at most `span_s` away: a logger's bursts a few
// minutes apart are bridged, a long interruption never is. Where only one
// neighbour qualifies the difference is one-sided; with none it is 0.
//
// The default span, 600 s, bridges the 305 s between the PAN log's bursts and
// stays well below the thermal time constants of a gyro block (tens of
// minutes), so a difference never reaches across a change of regime.

#include <map>
#include <string>
#include <vector>

#include "fit/data/averaging.h"
#include "sim/effects/effect.h"

namespace gyrotherm::fit {

enum class DerivativeMode { central, causal };
// "central" or "causal", as the fit file and reports write it.
const char* to_string(DerivativeMode mode);

// The effects' state series, and what only a measured log has: its other
// columns by name (window means) and their rates, for the terms named after
// them (fit/model/terms.h).
struct DerivedSeries : effects::EffectSeries {
  std::map<std::string, std::vector<double>, std::less<>> extra, extra_rate;
};

inline constexpr double kDefaultDerivativeSpanS = 600.0;

// sensor_tau_s: the temperature sensors' time constant τ (--sensor-tau). A
// sensor of first order reads T_s with T = T_s + τ·dT_s/dt, so the windows'
// temperatures are taken as T̄_s + τ·ẋ_w and their rates as ẋ_w + τ·ẍ_w
// (temp2 likewise): the terms see the gyro's temperature, not the lagged
// reading (errors in the regressors bias the rate terms most: dT and grad).
DerivedSeries derive(const AveragedSeries& data, DerivativeMode mode,
                     double span_s = kDefaultDerivativeSpanS, double sensor_tau_s = 0.0);

}  // namespace gyrotherm::fit
