#pragma once
// The rig as one ODE system for CVODE: the thermal network of sim/rig_config.h
// driven by the profile through the chamber controller.
//
// State y (all in SI units, temperatures in °C):
//   y[room..sensor2]   node temperatures (room, and the chamber when there is
//                      none, are boundary nodes with dT/dt = 0)
//   y[kIntegral]       the controller's integral term I, W
//   y[kHeaterEnergy]   ∫ u dt, energy put in by the chamber's heater/cooler, J
//   y[kLossEnergy]     ∫ q_boundary dt, energy lost to boundary nodes, J
//
//   C_i dT_i/dt = P_i + Σ q_{j→i}           (sim/thermal_network.h)
//   P_chamber = u(t)                        (sim/chamber_controller.h)
//   P_anode = P_discharge + P_dither/2,  P_far = P_dither/2,  P_case = P_electronics
//
// The temperature sensors are first-order lags: a node of small capacity C_s
// tied to its side of the block by G_s = C_s/τ_s, so dT_s/dt = (T_side − T_s)/τ_s.
//
// Energy conservation, checked by the tests:
//   Σ C_i ΔT_i = E_heater + P_self·t − E_loss.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "sim/chamber_controller.h"
#include "sim/cvode_solver.h"
#include "sim/profile.h"
#include "sim/rig_config.h"
#include "sim/thermal_network.h"

namespace gyrotherm::sim {

class RigDynamics : public OdeSystem {
 public:
  enum Node : std::size_t { room, chamber, case_, anode, far, sensor, sensor2, node_count };
  static constexpr std::size_t kIntegral = node_count;
  static constexpr std::size_t kHeaterEnergy = node_count + 1;
  static constexpr std::size_t kLossEnergy = node_count + 2;
  static constexpr std::size_t kStateSize = node_count + 3;
  static constexpr double kSensorCapacityJPerK = 0.5;  // a bonded platinum resistor

  // chamber_present = false: the chamber node is the room itself (a boundary).
  RigDynamics(const RigConfig& rig, const Profile& profile, double room_c, bool chamber_present);

  std::size_t size() const override { return kStateSize; }
  int rhs(double t, std::span<const double> y, std::span<double> ydot) override;

  // Every node at temp_c (the chamber and room at their own temperatures), the
  // controller's integral set to hold the chamber there with no error.
  std::vector<double> soaked_state(double temp_c) const;

  // Everything the right-hand side knows at (t, y), for outputs and tests.
  struct Observation {
    std::array<double, node_count> rates_k_per_s;
    double heater_w;        // controller output, + heating, − cooling
    double setpoint_c;
    double loss_w;          // heat flowing into boundary nodes
    double integral_rate;   // dI/dt of the controller
  };
  Observation observe(double t, std::span<const double> y) const;

  // What the simulator records at each sample, bit for bit as observe()
  // gives it, without the rest (the other nodes' rates, the losses).
  struct Sample {
    double anode_rate_k_per_s, heater_w, setpoint_c;
  };
  Sample sample(double t, std::span<const double> y) const;

  double self_heating_w() const;
  // Σ C_i T_i over the dynamic nodes, J (relative to 0 °C).
  double stored_energy_j(std::span<const double> y) const;

  const ThermalNetwork& network() const { return network_; }
  const Profile& profile() const { return profile_; }
  bool chamber_present() const { return chamber_present_; }
  double room_c() const { return room_c_; }

 private:
  RigConfig rig_;
  Profile profile_;
  double room_c_;
  bool chamber_present_;
  ChamberController controller_;
  ThermalNetwork network_;
};

}  // namespace gyrotherm::sim
