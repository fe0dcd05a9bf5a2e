#include "sim/bias_model.h"

namespace gyrotherm::sim {

BiasModel::BiasModel(const GyroConfig& gyro) : BiasModel(gyro.b0_dph, gyro.coefficient, gyro) {}

BiasModel::BiasModel(const ChannelConfig& channel, const GyroConfig& gyro)
    : BiasModel(channel.b0, channel.coefficient, gyro) {}

BiasModel::BiasModel(double b0, const std::map<std::string, double>& coefficient, const GyroConfig& gyro)
    : b0_dph_(b0) {
  for (const effects::Effect* e : effects::registry())
    if (const auto c = coefficient.find(std::string(e->name)); c != coefficient.end() && c->second != 0.0)
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
