#include "sim/bias_model.h"

namespace gyrotherm::sim {

BiasModel::BiasModel(const GyroConfig& gyro) : b0_dph_(gyro.b0_dph) {
  for (const effects::Effect* e : effects::registry())
    if (const double c = gyro.coefficient_of(*e); c != 0.0)
      active_.push_back({e, c, gyro.parameter_of(*e)});
}

BiasModel::BiasModel(const ChannelConfig& channel, const GyroConfig& gyro) : b0_dph_(channel.b0) {
  for (const effects::Effect* e : effects::registry())
    if (const auto c = channel.coefficient.find(std::string(e->name)); c != channel.coefficient.end() && c->second != 0.0)
      active_.push_back({e, c->second, gyro.parameter_of(*e)});
}

std::vector<double> BiasModel::bias_dph(const effects::EffectSeries& truth) const {
  std::vector<double> b(truth.size(), b0_dph_);
  std::vector<double> r(truth.size());
  for (const Active& a : active_) {
    a.effect->compute(truth, a.parameter, r);
    for (std::size_t k = 0; k < b.size(); ++k) b[k] += a.coefficient * r[k];
  }
  return b;
}

}  // namespace gyrotherm::sim
