#include "sim/chamber_controller.h"

#include <algorithm>

namespace gyrotherm::sim {

ChamberController::Output ChamberController::evaluate(double setpoint_c,
                                                      double setpoint_rate_c_per_s, double air_c,
                                                      double integral_w, bool on) const {
  if (!on) return {0.0, 0.0};
  const double error = setpoint_c - air_c;
  const double demand = config_.kp_w_per_k * error + integral_w +
                        config_.feedforward_j_per_k * setpoint_rate_c_per_s;
  const double power = std::clamp(demand, -config_.cooler_max_w, config_.heater_max_w);
  const double integral_rate =
      (config_.kp_w_per_k * error + (power - demand)) / config_.ti_s;
  return {power, integral_rate};
}

}  // namespace gyrotherm::sim
