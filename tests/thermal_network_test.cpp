// The heat-path formulas against textbook values, and conservation of energy.

#include "sim/thermal_network.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace gyrotherm::sim {
namespace {

TEST(ThermalNetwork, ConductionIsLinearAndAntisymmetric) {
  const ThermalLink link{0, 1, HeatPath::conduction, 2.5};
  EXPECT_DOUBLE_EQ(ThermalNetwork::flow_w(link, 30.0, 10.0), 50.0);
  EXPECT_DOUBLE_EQ(ThermalNetwork::flow_w(link, 10.0, 30.0), -50.0);
}

TEST(ThermalNetwork, RadiationMatchesStefanBoltzmannInKelvin) {
  const ThermalLink link{0, 1, HeatPath::radiation, 0.8 * 0.12};
  const double ta = 60.0 + 273.15, tb = -40.0 + 273.15;
  const double expected = 0.8 * 0.12 * 5.670374419e-8 * (std::pow(ta, 4) - std::pow(tb, 4));
  EXPECT_NEAR(ThermalNetwork::flow_w(link, 60.0, -40.0), expected, 1e-12 * std::abs(expected));
  // Small differences keep their digits (linearised: 4 ε σ A T³ ΔT).
  const double t = 293.15;
  const double linear = 0.8 * 0.12 * 5.670374419e-8 * 4.0 * t * t * t * 1e-6;
  EXPECT_NEAR(ThermalNetwork::flow_w(link, 20.0 + 5e-7, 20.0 - 5e-7), linear, 1e-6 * linear);
}

TEST(ThermalNetwork, NaturalConvectionGrowsAsQuarterPower) {
  const ThermalLink link{0, 1, HeatPath::natural_convection, 2.5};
  // hA is quoted at 10 K: there the flow is hA·ΔT.
  EXPECT_NEAR(ThermalNetwork::flow_w(link, 30.0, 20.0), 25.0, 1e-12);
  // At 160 K the effective h is 16^(1/4) = 2 times larger.
  EXPECT_NEAR(ThermalNetwork::flow_w(link, 180.0, 20.0), 2.5 * 160.0 * 2.0, 1e-9);
  EXPECT_NEAR(ThermalNetwork::flow_w(link, 20.0, 30.0), -25.0, 1e-12);
}

TEST(ThermalNetwork, RatesConserveEnergy) {
  ThermalNetwork net;
  const auto room = net.add_boundary("room");
  const auto a = net.add_node("a", 100.0);
  const auto b = net.add_node("b", 300.0);
  const auto c = net.add_node("c", 50.0);
  net.conduct(a, b, 0.7);
  net.convect(b, room, 1.3, /*natural=*/true);
  net.radiate(c, room, 0.9, 0.2);
  net.conduct(c, a, 0.2);
  const std::vector<double> temps = {23.0, 80.0, -10.0, 40.0};
  const std::vector<double> power = {0.0, 5.0, 0.0, 1.5};
  std::vector<double> rates(4);
  net.rates(temps, power, rates);
  EXPECT_EQ(rates[room], 0.0);
  const double stored_per_s = 100.0 * rates[a] + 300.0 * rates[b] + 50.0 * rates[c];
  EXPECT_NEAR(stored_per_s, 6.5 - net.flow_into_boundaries_w(temps), 1e-12);
}

TEST(ThermalNetwork, RejectsNonPositiveCapacity) {
  ThermalNetwork net;
  EXPECT_THROW(net.add_node("x", 0.0), std::invalid_argument);
  EXPECT_THROW(net.add_node("x", -1.0), std::invalid_argument);
}

}  // namespace
}  // namespace gyrotherm::sim
