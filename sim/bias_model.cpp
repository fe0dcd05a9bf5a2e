#include "sim/bias_model.h"

#include <cassert>
#include <cmath>

namespace gyrotherm::sim {

BiasModel::BiasModel(const GyroConfig& gyro) : truth_(gyro.truth), hidden_(gyro.hidden) {
  for (const auto& [name, coefficient] : hidden_.coefficient)
    if (coefficient != 0.0) active_.emplace_back(term_of(name), coefficient);
}

BiasModel::Term BiasModel::term_of(std::string_view name) {
  if (name == "grad") return Term::grad;
  if (name == "T*dT") return Term::t_dt;
  if (name == "T^3") return Term::t3;
  if (name == "d2T") return Term::d2t;
  if (name == "hyst") return Term::hyst;
  if (name == "warmup") return Term::warmup;
  assert(name == "t" && "unknown hidden term");
  return Term::drift;
}

double BiasModel::regressor(Term term, const TrueState& s) const {
  switch (term) {
    case Term::grad: return s.far_c - s.temp_c;
    case Term::t_dt: return s.temp_c * s.rate_c_per_s;
    case Term::t3: return s.temp_c * s.temp_c * s.temp_c;
    case Term::d2t: return s.accel_c_per_s2;
    case Term::hyst:
      if (s.rate_c_per_s > hidden_.hyst_dead_band_c_per_s) return 1.0;
      if (s.rate_c_per_s < -hidden_.hyst_dead_band_c_per_s) return -1.0;
      return 0.0;
    case Term::warmup: return std::exp(-s.since_switch_on_s / hidden_.warmup_time_constant_s);
    case Term::drift: return s.time_s / 3600.0;
  }
  return 0.0;
}

double BiasModel::hidden_regressor(std::string_view term, const TrueState& s) const {
  return regressor(term_of(term), s);
}

double BiasModel::bias_dph(const TrueState& s) const {
  double b = truth_.b0_dph + truth_.b1_dph_per_c * s.temp_c +
             truth_.b2_dph_per_c2 * s.temp_c * s.temp_c +
             truth_.b3_dph_per_c_per_s * s.rate_c_per_s;
  for (const auto& [term, coefficient] : active_) b += coefficient * regressor(term, s);
  return b;
}

}  // namespace gyrotherm::sim
