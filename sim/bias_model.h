#pragma once
// The true, noise-free gyro bias:
//
//   B = b0 + b1·T + b2·T² + b3·dT/dt + Σ_k c_k·r_k        [°/h]
//
// with T the true anode-side temperature (°C), dT/dt in °C/s, and r_k the
// hidden-effect regressors of sim/hidden_effects.h. Reference: the paper's
// eq. (6) (../shared/PAPER.md) for the first four terms.

#include <string_view>
#include <utility>
#include <vector>

#include "sim/gyro_config.h"

namespace gyrotherm::sim {

// The true physical state the bias depends on, at one instant.
struct TrueState {
  double time_s = 0.0;            // since the start of the record
  double since_switch_on_s = 0.0; // +inf when the record starts in equilibrium
  double temp_c = 0.0;            // anode side (sensor location)
  double far_c = 0.0;             // far side of the block
  double rate_c_per_s = 0.0;      // dT/dt
  double accel_c_per_s2 = 0.0;    // d²T/dt²
};

class BiasModel {
 public:
  explicit BiasModel(const GyroConfig& gyro);

  double bias_dph(const TrueState& s) const;
  // The regressor r_k of a hidden term (see hidden_effects.h).
  double hidden_regressor(std::string_view term, const TrueState& s) const;

 private:
  enum class Term { grad, t_dt, t3, d2t, hyst, warmup, drift };
  static Term term_of(std::string_view name);
  double regressor(Term term, const TrueState& s) const;

  TruthCoefficients truth_;
  HiddenEffects hidden_;
  std::vector<std::pair<Term, double>> active_;  // hidden terms with a non-zero coefficient
};

}  // namespace gyrotherm::sim
