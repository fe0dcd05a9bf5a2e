#pragma once
// The climatic chamber's temperature controller: PI with set-point-rate
// feed-forward, heater/cooler power limits and back-calculation anti-windup.
//
//   e = T_sp − T_air
//   v = Kp·e + I + K_ff·dT_sp/dt             (unsaturated demand, W)
//   u = clamp(v, −P_cool, +P_heat)            (power into the chamber air, W)
//   dI/dt = (Kp/Ti)·e + (u − v)/Ti            (the second term bleeds the integral
//                                               while saturated: anti-windup)
//
// The integral I is a state of the ODE, so the controller is integrated by
// CVODE together with the thermal network. When the chamber is off (a `free`
// segment) u = 0 and I is frozen.
//
// Reference: Åström & Hägglund, Advanced PID Control (ISA 2006), §3.5
// (windup, back-calculation) and §5.5 (feed-forward).

#include "sim/rig_config.h"

namespace gyrotherm::sim {

class ChamberController {
 public:
  explicit ChamberController(const ChamberConfig& config) : config_(config) {}

  struct Output {
    double power_w;            // u, applied to the chamber air
    double integral_rate_w_per_s;  // dI/dt
  };

  Output evaluate(double setpoint_c, double setpoint_rate_c_per_s, double air_c,
                  double integral_w, bool on) const;

  // The integral that makes the output equal power_w with zero error and a
  // constant set point (bumpless start from a steady state).
  double integral_for(double power_w) const { return power_w; }

 private:
  ChamberConfig config_;
};

}  // namespace gyrotherm::sim
