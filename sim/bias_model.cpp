#include "sim/bias_model.h"

#include <cassert>
#include <cmath>

namespace gyrotherm::sim {

BiasModel::BiasModel(const GyroConfig& gyro) : truth_(gyro.truth), hidden_(gyro.hidden) {}

double BiasModel::hidden_regressor(std::string_view term, const TrueState& s) const {
  if (term == "grad") return s.far_c - s.temp_c;
  if (term == "T*dT") return s.temp_c * s.rate_c_per_s;
  if (term == "T^3") return s.temp_c * s.temp_c * s.temp_c;
  if (term == "d2T") return s.accel_c_per_s2;
  if (term == "hyst") {
    if (s.rate_c_per_s > hidden_.hyst_dead_band_c_per_s) return 1.0;
    if (s.rate_c_per_s < -hidden_.hyst_dead_band_c_per_s) return -1.0;
    return 0.0;
  }
  if (term == "warmup") return std::exp(-s.since_switch_on_s / hidden_.warmup_time_constant_s);
  if (term == "t") return s.time_s / 3600.0;
  assert(false && "unknown hidden term");
  return 0.0;
}

double BiasModel::bias_dph(const TrueState& s) const {
  double b = truth_.b0_dph + truth_.b1_dph_per_c * s.temp_c +
             truth_.b2_dph_per_c2 * s.temp_c * s.temp_c +
             truth_.b3_dph_per_c_per_s * s.rate_c_per_s;
  for (const auto& [term, coefficient] : hidden_.coefficient)
    if (coefficient != 0.0) b += coefficient * hidden_regressor(term, s);
  return b;
}

}  // namespace gyrotherm::sim
