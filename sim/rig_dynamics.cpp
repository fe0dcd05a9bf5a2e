#include "sim/rig_dynamics.h"


namespace gyrotherm::sim {

RigDynamics::RigDynamics(const RigConfig& rig, const Profile& profile, double room_c,
                         bool chamber_present)
    : rig_(rig),
      profile_(profile),
      room_c_(room_c),
      chamber_present_(chamber_present),
      controller_(rig.chamber) {
  // Node order must match the Node enum.
  network_.add_boundary("room");
  if (chamber_present_)
    network_.add_node("chamber", rig.chamber.capacity_j_per_k);
  else
    network_.add_boundary("chamber");
  network_.add_node("case", rig.case_.capacity_j_per_k);
  network_.add_node("anode", rig.block.anode_capacity_j_per_k);
  network_.add_node("far", rig.block.far_capacity_j_per_k);
  network_.add_node("sensor", kSensorCapacityJPerK);
  network_.add_node("sensor2", kSensorCapacityJPerK);

  network_.conduct(chamber, room, rig.chamber.insulation_w_per_k);
  network_.convect(case_, chamber, rig.case_.convection_w_per_k, rig.case_.natural_convection);
  network_.radiate(case_, chamber, rig.case_.emissivity, rig.case_.area_m2);
  network_.conduct(anode, case_, rig.block.anode_case_w_per_k);
  network_.conduct(far, case_, rig.block.far_case_w_per_k);
  network_.conduct(anode, far, rig.block.anode_far_w_per_k);
  const double sensor_g = kSensorCapacityJPerK / rig.sensor.time_constant_s;
  network_.conduct(sensor, anode, sensor_g);
  network_.conduct(sensor2, far, sensor_g);
}

RigDynamics::Observation RigDynamics::observe(double t, std::span<const double> y) const {
  Observation o{};
  const std::span<const double> temps = y.first(node_count);
  const SetPoint sp = profile_.at(t);
  ChamberController::Output control{0.0, 0.0};
  if (chamber_present_)
    control = controller_.evaluate(sp.temp_c, sp.rate_c_per_s, temps[chamber], y[kIntegral],
                                   sp.chamber_on);
  std::array<double, node_count> power{};
  power[chamber] = control.power_w;
  power[anode] = rig_.power.discharge_w + 0.5 * rig_.power.dither_w;
  power[far] = 0.5 * rig_.power.dither_w;
  power[case_] = rig_.power.electronics_w;
  network_.rates(temps, power, o.rates_k_per_s);
  o.heater_w = control.power_w;
  o.setpoint_c = sp.temp_c;
  o.integral_rate = control.integral_rate_w_per_s;
  o.loss_w = network_.flow_into_boundaries_w(temps);
  return o;
}

RigDynamics::Sample RigDynamics::sample(double t, std::span<const double> y) const {
  const std::span<const double> temps = y.first(node_count);
  const SetPoint sp = profile_.at(t);
  ChamberController::Output control{0.0, 0.0};
  if (chamber_present_)
    control = controller_.evaluate(sp.temp_c, sp.rate_c_per_s, temps[chamber], y[kIntegral], sp.chamber_on);
  const double anode_power = rig_.power.discharge_w + 0.5 * rig_.power.dither_w;
  return {network_.rate_of(anode, temps, anode_power), control.power_w, sp.temp_c};
}

int RigDynamics::rhs(double t, std::span<const double> y, std::span<double> ydot) {
  const Observation o = observe(t, y);
  for (std::size_t i = 0; i < node_count; ++i) ydot[i] = o.rates_k_per_s[i];
  ydot[kIntegral] = o.integral_rate;
  ydot[kHeaterEnergy] = o.heater_w;
  ydot[kLossEnergy] = o.loss_w;
  return 0;
}

std::vector<double> RigDynamics::soaked_state(double temp_c) const {
  std::vector<double> y(kStateSize, 0.0);
  for (std::size_t i = 0; i < node_count; ++i) y[i] = temp_c;
  y[room] = room_c_;
  if (!chamber_present_) y[chamber] = room_c_;
  // Hold the chamber at temp_c: the controller supplies what the insulation loses.
  y[kIntegral] = chamber_present_
                     ? controller_.integral_for(rig_.chamber.insulation_w_per_k * (temp_c - room_c_))
                     : 0.0;
  return y;
}

double RigDynamics::self_heating_w() const {
  return rig_.power.discharge_w + rig_.power.dither_w + rig_.power.electronics_w;
}

double RigDynamics::stored_energy_j(std::span<const double> y) const {
  double e = 0.0;
  for (std::size_t i = 0; i < node_count; ++i)
    if (!network_.node(i).boundary) e += network_.node(i).capacity_j_per_k * y[i];
  return e;
}

}  // namespace gyrotherm::sim
