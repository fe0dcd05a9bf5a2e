#pragma once
// The true, noise-free gyro bias:
//
//   B = b0 + Σ_k c_k·r_k(θ_k)                                   [°/h]
//
// summed over the effects of the registry that are on (c_k ≠ 0), in registry
// order, each r_k the effect's own regressor (sim/effects/effect.h) evaluated
// on the true physical state. With the default gyro these are the paper's
// eq. (6) terms b1·T + b2·T² + b3·dT/dt (Yu, Xu, Wei, Long, Infrared and
// Laser Engineering 43(1):81-87, 2014).

#include <vector>

#include "sim/effects/effect.h"
#include "sim/gyro_config.h"

namespace gyrotherm::sim {

class BiasModel {
 public:
  explicit BiasModel(const GyroConfig& gyro);
  // A channel's (sim/channel.h): its b0 and coefficients, the gyro's
  // effect parameters; values in the channel's unit.
  BiasModel(const ChannelConfig& channel, const GyroConfig& gyro);

  // B at every point of the true state, in the gyro's (or channel's) unit.
  std::vector<double> bias_dph(const effects::EffectSeries& truth) const;

 private:
  // b0 and the coefficients by term name; the effects' parameters the gyro's.
  BiasModel(double b0, const std::map<std::string, double>& coefficient, const GyroConfig& gyro);
  struct Active {
    const effects::Effect* effect;
    double coefficient;
    double parameter;
  };
  double b0_dph_;
  std::vector<Active> active_;
};

}  // namespace gyrotherm::sim
