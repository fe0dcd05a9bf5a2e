#include "sim/thermal_network.h"

#include <cassert>
#include <cmath>
#include <stdexcept>

namespace gyrotherm::sim {

std::size_t ThermalNetwork::add_node(std::string name, double capacity_j_per_k) {
  if (!(capacity_j_per_k > 0.0))
    throw std::invalid_argument("thermal node '" + name + "' needs a positive capacity");
  nodes_.push_back({std::move(name), capacity_j_per_k, false});
  return nodes_.size() - 1;
}

std::size_t ThermalNetwork::add_boundary(std::string name) {
  nodes_.push_back({std::move(name), 0.0, true});
  return nodes_.size() - 1;
}

void ThermalNetwork::check_pair(std::size_t a, std::size_t b) const {
  if (a >= nodes_.size() || b >= nodes_.size() || a == b)
    throw std::invalid_argument("thermal link between invalid nodes");
}

void ThermalNetwork::conduct(std::size_t a, std::size_t b, double conductance_w_per_k) {
  check_pair(a, b);
  links_.push_back({a, b, HeatPath::conduction, conductance_w_per_k});
}

void ThermalNetwork::convect(std::size_t a, std::size_t b, double ha_w_per_k, bool natural) {
  check_pair(a, b);
  links_.push_back(
      {a, b, natural ? HeatPath::natural_convection : HeatPath::forced_convection, ha_w_per_k});
}

void ThermalNetwork::radiate(std::size_t a, std::size_t b, double emissivity, double area_m2) {
  check_pair(a, b);
  links_.push_back({a, b, HeatPath::radiation, emissivity * area_m2});
}

double ThermalNetwork::flow_w(const ThermalLink& link, double temp_a_c, double temp_b_c) {
  const double dt = temp_a_c - temp_b_c;
  switch (link.path) {
    case HeatPath::conduction:
    case HeatPath::forced_convection:
      return link.coefficient * dt;
    case HeatPath::natural_convection:
      return link.coefficient * dt * std::pow(std::abs(dt) / kNaturalConvectionReferenceK, 0.25);
    case HeatPath::radiation: {
      const double ta = temp_a_c + kKelvinOffset;
      const double tb = temp_b_c + kKelvinOffset;
      // T_a⁴ − T_b⁴ factored to keep digits when the two are close.
      return link.coefficient * kStefanBoltzmann * (ta - tb) * (ta + tb) * (ta * ta + tb * tb);
    }
  }
  return 0.0;
}

void ThermalNetwork::rates(std::span<const double> temp_c, std::span<const double> power_w,
                           std::span<double> rate_k_per_s) const {
  assert(temp_c.size() == nodes_.size() && power_w.size() == nodes_.size() &&
         rate_k_per_s.size() == nodes_.size());
  // First accumulate net heat into each node (W), then divide by capacity.
  for (std::size_t i = 0; i < nodes_.size(); ++i) rate_k_per_s[i] = power_w[i];
  for (const ThermalLink& link : links_) {
    const double q = flow_w(link, temp_c[link.a], temp_c[link.b]);
    rate_k_per_s[link.a] -= q;
    rate_k_per_s[link.b] += q;
  }
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    rate_k_per_s[i] = nodes_[i].boundary ? 0.0 : rate_k_per_s[i] / nodes_[i].capacity_j_per_k;
}

double ThermalNetwork::rate_of(std::size_t node, std::span<const double> temp_c, double power_w) const {
  double rate = power_w;
  for (const ThermalLink& link : links_) {
    if (link.a != node && link.b != node) continue;
    const double q = flow_w(link, temp_c[link.a], temp_c[link.b]);
    if (link.a == node) rate -= q;
    if (link.b == node) rate += q;
  }
  return nodes_[node].boundary ? 0.0 : rate / nodes_[node].capacity_j_per_k;
}

double ThermalNetwork::flow_into_boundaries_w(std::span<const double> temp_c) const {
  double total = 0.0;
  for (const ThermalLink& link : links_) {
    const double q = flow_w(link, temp_c[link.a], temp_c[link.b]);
    if (nodes_[link.b].boundary) total += q;
    if (nodes_[link.a].boundary) total -= q;
  }
  return total;
}

}  // namespace gyrotherm::sim
