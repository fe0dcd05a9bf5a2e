#include "sim/gyro_config.h"

namespace gyrotherm::sim {

double GyroConfig::coefficient_of(const effects::Effect& effect) const {
  const auto it = coefficient.find(std::string(effect.name));
  return it == coefficient.end() ? 0.0 : it->second;
}

double GyroConfig::parameter_of(const effects::Effect& effect) const {
  if (!effect.parameter) return 0.0;
  const auto it = parameter.find(std::string(effect.name));
  return it == parameter.end() ? effect.parameter->simulator_default : it->second;
}

std::map<std::string, double> true_coefficients(const GyroConfig& gyro) {
  std::map<std::string, double> truth = {{"1", gyro.b0_dph}};
  for (const effects::Effect* e : effects::registry())
    if (const double c = gyro.coefficient_of(*e); c != 0.0) truth[std::string(e->name)] = c;
  return truth;
}

}  // namespace gyrotherm::sim
