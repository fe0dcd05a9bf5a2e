#pragma once
// A lumped-capacity thermal network.
//
// Every node i has a heat capacity C_i (J/K) and a temperature T_i (°C); it
// receives external power P_i (W) and heat flows q_ji from the links that touch
// it:
//
//     C_i dT_i/dt = P_i + Σ_links q_{j→i}
//
// Heat paths (the flow from a to b):
//   conduction          q = G (T_a − T_b)                       G  in W/K
//   forced convection   q = hA (T_a − T_b)                      hA in W/K
//   natural convection  q = hA (T_a − T_b) (|T_a − T_b| / 10 K)^(1/4)
//                       (laminar free convection, h ∝ ΔT^(1/4); hA is quoted
//                        at a 10 K difference)
//   radiation           q = ε σ A (T_a⁴ − T_b⁴), temperatures in kelvin
//                       (a small grey body a inside a large enclosure b)
//
// Boundary nodes have an imposed temperature: their rate is zero and the heat
// they absorb leaves the system (the room, or a chamber that is not simulated).
// Every link is antisymmetric, so energy is conserved exactly:
//     Σ_i C_i dT_i/dt = Σ_i P_i − (heat into boundary nodes).
//
// Reference: Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, ch. 1,
// 5 (lumped capacitance), 9 (free convection), 13 (radiation exchange).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace gyrotherm::sim {

inline constexpr double kStefanBoltzmann = 5.670374419e-8;  // W m⁻² K⁻⁴
inline constexpr double kKelvinOffset = 273.15;
inline constexpr double kNaturalConvectionReferenceK = 10.0;

enum class HeatPath { conduction, forced_convection, natural_convection, radiation };

struct ThermalNode {
  std::string name;
  double capacity_j_per_k = 0.0;  // 0 for a boundary node
  bool boundary = false;
};

struct ThermalLink {
  std::size_t a = 0;
  std::size_t b = 0;
  HeatPath path = HeatPath::conduction;
  // G or hA in W/K for conduction and convection; ε·A in m² for radiation.
  double coefficient = 0.0;
};

class ThermalNetwork {
 public:
  std::size_t add_node(std::string name, double capacity_j_per_k);
  std::size_t add_boundary(std::string name);

  void conduct(std::size_t a, std::size_t b, double conductance_w_per_k);
  void convect(std::size_t a, std::size_t b, double ha_w_per_k, bool natural = false);
  void radiate(std::size_t a, std::size_t b, double emissivity, double area_m2);

  std::size_t size() const { return nodes_.size(); }
  const ThermalNode& node(std::size_t i) const { return nodes_[i]; }
  const std::vector<ThermalLink>& links() const { return links_; }

  // Heat flow from link.a to link.b, W.
  static double flow_w(const ThermalLink& link, double temp_a_c, double temp_b_c);

  // dT/dt of every node in K/s (zero for boundary nodes). power_w is the
  // external power into each node. Does not allocate.
  void rates(std::span<const double> temp_c, std::span<const double> power_w,
             std::span<double> rate_k_per_s) const;

  // dT/dt of one node (K/s), the same arithmetic in the same order as rates()
  // gives it, from the links that touch it only.
  double rate_of(std::size_t node, std::span<const double> temp_c, double power_w) const;

  // Total heat flowing into boundary nodes, W (what the system loses).
  double flow_into_boundaries_w(std::span<const double> temp_c) const;

 private:
  void check_pair(std::size_t a, std::size_t b) const;
  std::vector<ThermalNode> nodes_;
  std::vector<ThermalLink> links_;
};

}  // namespace gyrotherm::sim
