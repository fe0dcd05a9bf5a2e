#pragma once
// The per-trial spread of a gyro's parameters (a scenario's [spread] table):
// each trial draws p = p₀·(1 + r·u), u ~ U(−1, 1) from make_rng(s_k,
// streams::score_spread), one draw per key of sim::kSpreadKeys in that order, so a
// key's draw never depends on which other keys are spread.

#include <cstdint>
#include <map>
#include <string>

#include "sim/gyro_config.h"
#include "sim/util/random.h"

namespace gyrotherm::studies {

// Per-trial spread of the gyro's parameters (step 2 above).
sim::GyroConfig apply_spread(const sim::GyroConfig& gyro, const std::map<std::string, double>& spread,
                             std::uint64_t trial_seed);


}  // namespace gyrotherm::studies
