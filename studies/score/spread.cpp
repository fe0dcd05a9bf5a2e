#include "studies/score/spread.h"

#include <boost/random/uniform_real_distribution.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cassert>

#include "sim/config_loader.h"
#include "sim/util/input_error.h"

namespace gyrotherm::studies {

namespace {

double& spread_target(sim::GyroConfig& g, std::string_view key) {
  if (key == "b0_dph") return g.b0_dph;
  // The [truth] key of one of the paper's effects (sim/effects/).
  if (const effects::Effect* e = effects::find_by_truth_key(key))
    return g.coefficient[std::string(e->name)];
  if (key == "arw_deg_per_sqrt_h") return g.noise.arw_deg_per_sqrt_h;
  if (key == "bias_instability_dph") return g.noise.bias_instability_dph;
  if (key == "rrw_dph_per_sqrt_h") return g.noise.rrw_dph_per_sqrt_h;
  if (key == "quantization_arcsec") return g.noise.quantization_arcsec;
  if (key == "glitch_rate_per_h") return g.noise.glitch_rate_per_h;
  if (key == "glitch_size_dph") return g.noise.glitch_size_dph;
  assert(false && "spread_target: a key outside sim::kSpreadKeys");
  return g.b0_dph;
}

}  // namespace

sim::GyroConfig apply_spread(const sim::GyroConfig& gyro, const std::map<std::string, double>& spread,
                             std::uint64_t trial_seed) {
  sim::GyroConfig g = gyro;
  if (spread.empty()) return g;
  for (const auto& [key, r] : spread) {
    if (std::find(sim::kSpreadKeys.begin(), sim::kSpreadKeys.end(), key) == sim::kSpreadKeys.end())
      throw InputError(fmt::format("[spread]: unknown key '{}'", key));
    if (!(r >= 0.0 && r < 1.0))
      throw InputError(fmt::format("[spread]: {} = {}: must be >= 0 and < 1", key, r));
  }
  Rng rng = make_rng(trial_seed, streams::score_spread);
  boost::random::uniform_real_distribution<double> unit(-1.0, 1.0);
  // One draw per key, spread or not, so each key's draw is fixed by the seed alone.
  for (const std::string_view key : sim::kSpreadKeys) {
    const double u = unit(rng);
    const auto it = spread.find(std::string(key));
    if (it == spread.end()) continue;
    spread_target(g, key) *= 1.0 + it->second * u;
  }
  return g;
}

}  // namespace gyrotherm::studies
