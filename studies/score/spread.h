#pragma once
// The per-trial spread of a gyro's parameters (a scenario's [spread] table):
// each trial draws p = p₀·(1 + r·u), u ~ U(−1, 1) from make_rng(s_k,
// kSpreadStream), one draw per key of sim::kSpreadKeys in that order, so a
// key's draw never depends on which other keys are spread.

#include <cstdint>
#include <map>
#include <string>

#include "sim/gyro_config.h"
#include "sim/util/random.h"

namespace gyrotherm::fit {

// The generator stream of the [spread] draws (sim/util/random.h): apart from
// the simulator's noise streams and the engines' own.
inline constexpr std::uint64_t kSpreadStream = 0x5C0E;

// Per-trial spread of the gyro's parameters (step 2 above).
sim::GyroConfig apply_spread(const sim::GyroConfig& gyro, const std::map<std::string, double>& spread,
                             std::uint64_t trial_seed);


}  // namespace gyrotherm::fit
