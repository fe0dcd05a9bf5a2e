// The simulator against physics and statistics it must honour:
//  - the chamber holds ±0.1 °C in the soaks of the shipped cycle;
//  - energy is conserved over whole runs (chamber, free drift, no chamber);
//  - the "steady" initial condition is the algebraic steady state;
//  - the natural warm-up settles where self-heating equals convection plus radiation;
//  - with only ARW on, the output's Allan deviation is N/√τ within 10 %;
//  - with only quantisation on, 100 s averages are off by less than one pulse / 100 s;
//  - the same seed gives the same record, another seed a different one;
//  - hidden effects add exactly c·r(t) to the true bias.

#include "sim/simulator.h"

#include "sim/effects/effect.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "studies/allan/allan_curve.h"
#include "sim/config_loader.h"
#include "sim/output.h"

namespace gyrotherm::sim {
namespace {

using N = RigDynamics::Node;

std::string scenario_path(const std::string& name) {
  return std::string(GYROTHERM_SOURCE_DIR) + "/scenarios/" + name + ".toml";
}

Simulator shipped(const std::string& name) {
  const Scenario s = load_scenario(scenario_path(name));
  return Simulator(s, load_rig(s.rig_file), load_gyro(s.gyro_file));
}

// A gyro with every noise source off and a constant true bias.
GyroConfig quiet_constant_gyro() {
  GyroConfig g;
  g.b0_dph = -7.0;
  g.coefficient.clear();
  g.noise.arw_deg_per_sqrt_h = 0.0;
  g.noise.bias_instability_dph = 0.0;
  g.noise.rrw_dph_per_sqrt_h = 0.0;
  g.noise.quantization_arcsec = 0.0;
  g.noise.glitch_rate_per_h = 0.0;
  g.noise.arw_temp_coeff_per_c2 = 0.0;
  return g;
}

Scenario hold_scenario(double hours, std::uint64_t seed) {
  Scenario s;
  s.name = "hold";
  s.seed = seed;
  s.start_c = 20.0;
  s.initial = InitialCondition::steady;
  s.segments = {Segment{SegmentKind::hold, 20.0, 0.0, hours * 3600.0, 0}};
  return s;
}

TEST(Simulator, ChamberHoldsPointOneDegreeInTheCycleSoaks) {
  const Simulator sim = shipped("cycle");
  const ThermalTrace tr = sim.run_thermal();
  const Profile profile(sim.scenario().start_c, sim.scenario().segments);
  double worst = 0.0;
  std::size_t soak_samples = 0;
  for (std::size_t k = 0; k < tr.time_s.size(); ++k) {
    const std::size_t s = profile.segment_at(tr.time_s[k]);
    if (profile.segments()[s].kind != SegmentKind::hold) continue;
    ++soak_samples;
    worst = std::max(worst, std::abs(tr.node(N::chamber)[k] - tr.setpoint_c[k]));
  }
  EXPECT_GT(soak_samples, 4u * 7000u);
  EXPECT_LE(worst, 0.1) << "worst soak deviation " << worst << " °C";
  // The gyro really travels the cycle, lagging the chamber (the calibrated
  // shield rig has a slowest time constant of about 1.5 h, results/calibration.md).
  const auto& gyro = tr.node(N::anode);
  EXPECT_LT(*std::min_element(gyro.begin(), gyro.end()), 0.0);
  EXPECT_GT(*std::max_element(gyro.begin(), gyro.end()), 45.0);
}

TEST(Simulator, ChamberLagsButFollowsTheRamps) {
  const Simulator sim = shipped("cycle");
  const ThermalTrace tr = sim.run_thermal();
  double worst = 0.0;
  for (std::size_t k = 0; k < tr.time_s.size(); ++k)
    worst = std::max(worst, std::abs(tr.node(N::chamber)[k] - tr.setpoint_c[k]));
  EXPECT_LT(worst, 2.0);  // a 5 °C/min chamber tracks within a couple of degrees
}

class EnergyBalanceTest : public ::testing::TestWithParam<std::string> {};

TEST_P(EnergyBalanceTest, EnergyIsConservedOverTheRun) {
  const Simulator sim = shipped(GetParam());
  SolverStatistics stats;
  EnergyBalance e;
  sim.run_thermal(&stats, &e);
  const double scale = std::max({std::abs(e.heater_j), e.self_heating_j, std::abs(e.lost_j),
                                 std::abs(e.stored_change_j)});
  EXPECT_GT(e.self_heating_j, 0.0);
  EXPECT_LT(std::abs(e.residual_j()), 1e-6 * scale)
      << "stored " << e.stored_change_j << " heater " << e.heater_j << " self "
      << e.self_heating_j << " lost " << e.lost_j;
  EXPECT_GT(stats.steps, 0);
}

INSTANTIATE_TEST_SUITE_P(ShippedScenarios, EnergyBalanceTest,
                         ::testing::Values("cycle", "random", "warmup"));

TEST(Simulator, SteadyInitialConditionIsTheAlgebraicSteadyState) {
  // A linear rig (forced convection, no radiation) so the steady state solves
  // L (T − T_chamber) = P exactly; the controller's integral action puts the
  // chamber exactly on its set point.
  RigConfig rig;
  rig.case_.emissivity = 0.0;
  rig.case_.natural_convection = false;
  rig.power.electronics_w = 5.0;
  Scenario s = hold_scenario(0.5, 1);
  s.start_c = -15.0;
  s.segments[0].temp_c = -15.0;
  const Simulator sim(s, rig, quiet_constant_gyro());
  const ThermalTrace tr = sim.run_thermal();

  const double h = rig.case_.convection_w_per_k;
  const BlockConfig& b = rig.block;
  Eigen::Matrix3d L;  // case, anode, far
  L << h + b.anode_case_w_per_k + b.far_case_w_per_k, -b.anode_case_w_per_k, -b.far_case_w_per_k,
      -b.anode_case_w_per_k, b.anode_case_w_per_k + b.anode_far_w_per_k, -b.anode_far_w_per_k,
      -b.far_case_w_per_k, -b.anode_far_w_per_k, b.anode_far_w_per_k + b.far_case_w_per_k;
  const Eigen::Vector3d P(5.0, rig.power.discharge_w + 0.5 * rig.power.dither_w,
                          0.5 * rig.power.dither_w);
  const Eigen::Vector3d T = (L.ldlt().solve(P).array() - 15.0).matrix();
  for (std::size_t k : {std::size_t{0}, tr.time_s.size() - 1}) {
    EXPECT_NEAR(tr.node(N::chamber)[k], -15.0, 1e-6);
    EXPECT_NEAR(tr.node(N::case_)[k], T[0], 1e-6);
    EXPECT_NEAR(tr.node(N::anode)[k], T[1], 1e-6);
    EXPECT_NEAR(tr.node(N::far)[k], T[2], 1e-6);
    EXPECT_NEAR(tr.node(N::sensor)[k], T[1], 1e-6);
    EXPECT_NEAR(tr.node(N::sensor2)[k], T[2], 1e-6);
  }
}

TEST(Simulator, NaturalWarmUpSettlesWhereSelfHeatingEqualsTheLosses) {
  const Simulator sim = shipped("warmup");
  const ThermalTrace tr = sim.run_thermal();
  const std::size_t end = tr.time_s.size() - 1;
  const RigConfig& rig = sim.rig();
  const double room = sim.scenario().room_c;
  // Equilibrium: P = hA ΔT (ΔT/10 K)^¼ + ε σ A (T⁴ − T_room⁴), by hand.
  const double t_case = tr.node(N::case_)[end];
  const double dt = t_case - room;
  const double convection = rig.case_.convection_w_per_k * dt * std::pow(dt / 10.0, 0.25);
  const double radiation = rig.case_.emissivity * rig.case_.area_m2 * 5.670374419e-8 *
                           (std::pow(t_case + 273.15, 4) - std::pow(room + 273.15, 4));
  const double self_heating =
      rig.power.discharge_w + rig.power.dither_w + rig.power.electronics_w;
  EXPECT_NEAR(convection + radiation, self_heating, 1e-3 * self_heating);
  EXPECT_GT(dt, 2.0);
  EXPECT_LT(std::abs(tr.anode_rate_c_per_s[end]), 1e-6);
  // No chamber: the "chamber" is the room.
  EXPECT_EQ(tr.node(N::chamber)[end], room);
}

TEST(Simulator, FreeSegmentDriftsTowardsTheFreeEquilibrium) {
  // With the chamber off, all the INS's dissipation must finally leave through
  // the chamber's insulation, so the chamber heads for room + P_self / G_ins
  // (31.8 °C for 26.3 W through 3 W/K; the paper: "let the system warm up
  // naturally"), from 25 °C, without power and without overshooting.
  const Simulator sim = shipped("random");
  const ThermalTrace tr = sim.run_thermal();
  const Profile profile(sim.scenario().start_c, sim.scenario().segments);
  const std::size_t last = profile.segments().size() - 1;
  ASSERT_EQ(profile.segments()[last].kind, SegmentKind::free);
  const double start = profile.segment_start_s(last);
  std::size_t k0 = 0;
  while (tr.time_s[k0] < start) ++k0;
  const auto& chamber = tr.node(N::chamber);
  const RigConfig& rig = sim.rig();
  const double self = rig.power.discharge_w + rig.power.dither_w + rig.power.electronics_w;
  const double equilibrium = sim.scenario().room_c + self / rig.chamber.insulation_w_per_k;
  for (std::size_t k = k0 + 1; k < tr.time_s.size(); ++k) {
    EXPECT_EQ(tr.heater_w[k], 0.0);
    EXPECT_GE(chamber[k], chamber[k - 1] - 1e-9);  // monotonic towards equilibrium (above)
    EXPECT_LT(chamber[k], equilibrium);
  }
  EXPECT_GT(chamber.back(), chamber[k0] + 1.0);
}

TEST(Simulator, SwitchedOffLinearRigMatchesTheExactSolution) {
  // Chamber off, forced convection, no radiation, no self-heating: the whole
  // simulator (profile, controller off, six nodes) against the exact solution
  // of C Ṫ = −L (T − T_room) by eigen-decomposition, to 1e-6 K.
  RigConfig rig;
  rig.power = {0.0, 0.0, 0.0};
  rig.case_.emissivity = 0.0;
  Scenario s;
  s.room_c = 23.0;
  s.start_c = 60.0;
  s.segments = {Segment{SegmentKind::free, 0.0, 0.0, 10.0 * 3600.0, 0}};
  SimulationOptions tight;
  tight.solver.relative_tolerance = 1e-11;
  for (double& a : tight.solver.absolute_tolerance) a *= 1e-5;
  const ThermalTrace tr = Simulator(s, rig, GyroConfig{}, tight).run_thermal();

  // Nodes: chamber, case, anode, far, sensor, sensor2.
  constexpr int n = 6;
  const double cs = RigDynamics::kSensorCapacityJPerK;
  const double gs = cs / rig.sensor.time_constant_s;
  const Eigen::Matrix<double, n, 1> C =
      (Eigen::Matrix<double, n, 1>() << rig.chamber.capacity_j_per_k, rig.case_.capacity_j_per_k,
       rig.block.anode_capacity_j_per_k, rig.block.far_capacity_j_per_k, cs, cs)
          .finished();
  Eigen::Matrix<double, n, n> L = Eigen::Matrix<double, n, n>::Zero();
  auto link = [&](int i, int j, double g) {
    L(i, i) += g;
    L(j, j) += g;
    L(i, j) -= g;
    L(j, i) -= g;
  };
  L(0, 0) += rig.chamber.insulation_w_per_k;  // chamber to the room
  link(0, 1, rig.case_.convection_w_per_k);
  link(1, 2, rig.block.anode_case_w_per_k);
  link(1, 3, rig.block.far_case_w_per_k);
  link(2, 3, rig.block.anode_far_w_per_k);
  link(4, 2, gs);
  link(5, 3, gs);
  const Eigen::Matrix<double, n, 1> sq = C.cwiseSqrt();
  const Eigen::Matrix<double, n, n> A = sq.cwiseInverse().asDiagonal() * L * sq.cwiseInverse().asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, n, n>> eig(A);
  ASSERT_EQ(eig.info(), Eigen::Success);
  const Eigen::Matrix<double, n, 1> z0 =
      eig.eigenvectors().transpose() * sq.cwiseProduct(Eigen::Matrix<double, n, 1>::Constant(37.0));
  const N nodes[n] = {N::chamber, N::case_, N::anode, N::far, N::sensor, N::sensor2};
  for (std::size_t k = 0; k < tr.time_s.size(); k += 977) {
    const double t = tr.time_s[k];
    const Eigen::Matrix<double, n, 1> z = z0.cwiseProduct((-eig.eigenvalues() * t).array().exp().matrix());
    const Eigen::Matrix<double, n, 1> excess = (eig.eigenvectors() * z).cwiseQuotient(sq);
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(tr.node(nodes[i])[k], 23.0 + excess[i], 1e-6) << "node " << i << " t " << t;
  }
}

TEST(Simulator, TheLongestProfileLastsAboutThreeDays) {
  const Scenario s = load_scenario(scenario_path("random"));
  const Profile p(s.start_c, s.segments);
  EXPECT_NEAR(p.duration_s() / 3600.0, 72.0, 1.0);
}

TEST(Simulator, AllanDeviationWithOnlyArwIsNOverRootTau) {
  const double n_dpsh = 3e-4;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    GyroConfig g = quiet_constant_gyro();
    g.noise.arw_deg_per_sqrt_h = n_dpsh;
    const Simulator sim(hold_scenario(100.0, seed), RigConfig{}, g);
    const SimulationResult r = sim.run();
    const std::vector<double> taus = {1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0};
    for (const double tau : taus) {
      const double expected = n_dpsh / std::sqrt(tau / 3600.0);
      const double adev = studies::overlapping_adev(r.gyro_dph, static_cast<std::size_t>(tau));
      EXPECT_NEAR(adev / expected, 1.0, 0.10) << "seed " << seed << " tau " << tau;
    }
  }
}

TEST(Simulator, QuantisationErrorOfHundredSecondAveragesStaysBounded) {
  GyroConfig g = quiet_constant_gyro();
  g.b0_dph = -7.07712;  // a bias that moves with the cycle
  g.coefficient = {{"T", -3.05e-4}, {"T^2", 1.06e-6}, {"dT", 1.81}};
  g.noise.quantization_arcsec = 1.0;               // coarse pulses: 1 °/h per 1 s sample
  Scenario s = load_scenario(scenario_path("cycle"));
  const Simulator sim(s, load_rig(s.rig_file), g);
  const SimulationResult r = sim.run();
  const double q = 1.0;
  double worst = 0.0;
  for (std::size_t start = 0; start + 100 <= r.rows(); start += 100) {
    double out = 0.0, truth = 0.0;
    for (std::size_t k = start; k < start + 100; ++k) {
      out += r.gyro_dph[k];
      truth += r.bias_true_dph[k];
    }
    worst = std::max(worst, std::abs(out - truth) / 100.0);
  }
  // Each 1 s sample is off by up to 1 °/h, but pulses are counted on the
  // accumulated angle, so a 100 s mean is off by less than q / 100 s.
  EXPECT_LE(worst, q / 100.0 + 1e-9);
  EXPECT_GT(worst, 0.1 * q / 100.0);  // quantisation is really on
}

TEST(Simulator, SameSeedSameRecordOtherSeedDifferent) {
  Scenario s = load_scenario(scenario_path("cycle"));
  const RigConfig rig = load_rig(s.rig_file);
  const GyroConfig gyro = load_gyro(s.gyro_file);
  const Simulator a(s, rig, gyro);
  const Simulator b(s, rig, gyro);
  s.seed += 1;
  const Simulator c(s, rig, gyro);
  const std::string text_a = simulation_csv(a, a.run());
  EXPECT_EQ(text_a, simulation_csv(b, b.run()));
  EXPECT_NE(text_a, simulation_csv(c, c.run()));
}

// What `score` relies on: one thermal trace serves every seed and every
// [truth]/[noise] variant, and record() on it is run() to the bit.
TEST(Simulator, RecordOnASharedTraceIsRunForEverySeedAndGyro) {
  Scenario s = load_scenario(scenario_path("cycle"));
  const RigConfig rig = load_rig(s.rig_file);
  const GyroConfig gyro = load_gyro(s.gyro_file);
  const ThermalTrace trace = Simulator(s, rig, gyro).run_thermal();
  GyroConfig other = gyro;
  other.coefficient.at("T") *= 1.1;
  other.noise.arw_deg_per_sqrt_h *= 0.9;
  for (const GyroConfig& g : {gyro, other})
    for (const std::uint64_t seed : {s.seed, s.seed + 5}) {
      Scenario sk = s;
      sk.seed = seed;
      const Simulator sim(sk, rig, g);
      const SimulationResult shared = sim.record(trace);
      EXPECT_EQ(simulation_csv(sim, shared), simulation_csv(sim, sim.run())) << "seed " << seed;
      EXPECT_EQ(shared.seed, seed);
    }
}

TEST(Simulator, HiddenEffectsAddExactlyTheirTerm) {
  Scenario s = load_scenario(scenario_path("cycle"));
  const RigConfig rig = load_rig(s.rig_file);
  const GyroConfig plain = load_gyro(s.gyro_file);
  const SimulationResult base = Simulator(s, rig, plain).run();
  const ThermalTrace& tr = base.truth;

  GyroConfig grad = plain;
  grad.coefficient["grad"] = 0.01;
  const SimulationResult with_grad = Simulator(s, rig, grad).run();
  GyroConfig warm = plain;
  warm.coefficient["warmup"] = 0.02;
  const SimulationResult with_warm = Simulator(s, rig, warm).run();
  GyroConfig hyst = plain;
  hyst.coefficient["hyst"] = 0.003;
  const SimulationResult with_hyst = Simulator(s, rig, hyst).run();

  int heating = 0, cooling = 0;
  for (std::size_t k = 0; k < base.rows(); k += 7) {
    const double grad_c = tr.node(N::far)[k] - tr.node(N::anode)[k];
    EXPECT_NEAR(with_grad.bias_true_dph[k] - base.bias_true_dph[k], 0.01 * grad_c, 1e-12);
    EXPECT_NEAR(with_warm.bias_true_dph[k] - base.bias_true_dph[k],
                0.02 * std::exp(-tr.time_s[k] / plain.parameter_of(*effects::find("warmup"))), 1e-12);
    const double rate = tr.anode_rate_c_per_s[k];
    const double sign = rate > plain.parameter_of(*effects::find("hyst"))    ? 1.0
                        : rate < -plain.parameter_of(*effects::find("hyst")) ? -1.0
                                                                      : 0.0;
    heating += sign > 0;
    cooling += sign < 0;
    EXPECT_NEAR(with_hyst.bias_true_dph[k] - base.bias_true_dph[k], 0.003 * sign, 1e-12);
  }
  EXPECT_GT(heating, 100);
  EXPECT_GT(cooling, 100);
  // The noise realisation does not depend on the hidden effects.
  for (std::size_t k = 0; k < base.rows(); k += 1000)
    EXPECT_EQ(with_grad.temp_c[k], base.temp_c[k]);
}

// Every effect of the registry is injected as c·r, r its regressor on the
// true state: the anode side's temperature, its exact rate and the rate's
// central differences, the far side, time since the start of a soaked record.
// (The regressors' formulas are checked by hand in effects_test.cpp.)
TEST(Simulator, EveryEffectIsInjectedOnTheTrueState) {
  Scenario s = load_scenario(scenario_path("cycle"));
  s.segments.resize(3);  // soak, ramp up, soak: about 2.6 h
  const RigConfig rig = load_rig(s.rig_file);
  GyroConfig off = load_gyro(s.gyro_file);
  off.coefficient.clear();
  const SimulationResult base = Simulator(s, rig, off).run();
  const ThermalTrace& tr = base.truth;
  effects::EffectSeries state;
  state.time_s = tr.time_s;
  state.temp_c = tr.node(N::anode);
  state.temp2_c = tr.node(N::far);
  state.rate_c_per_s = tr.anode_rate_c_per_s;
  state.accel_c_per_s2.resize(tr.time_s.size());
  for (std::size_t k = 1; k + 1 < tr.time_s.size(); ++k)
    state.accel_c_per_s2[k] = (tr.anode_rate_c_per_s[k + 1] - tr.anode_rate_c_per_s[k - 1]) /
                              (tr.time_s[k + 1] - tr.time_s[k - 1]);
  for (const effects::Effect* e : effects::registry()) {
    GyroConfig on = off;
    on.coefficient[std::string(e->name)] = 0.01;
    const SimulationResult with = Simulator(s, rig, on).run();
    const std::vector<double> r = effects::regressor_values(*e, state, on.parameter_of(*e));
    double largest = 0.0;
    for (std::size_t k = 1; k + 1 < base.rows(); k += 13) {
      ASSERT_NEAR(with.bias_true_dph[k] - base.bias_true_dph[k], 0.01 * r[k], 1e-12 + 1e-12 * std::abs(r[k]))
          << e->name << " at t = " << tr.time_s[k];
      largest = std::max(largest, std::abs(r[k]));
    }
    EXPECT_GT(largest, 0.0) << e->name << ": the cycle's first ramp should excite every effect";
    EXPECT_EQ(with.temp_c, base.temp_c) << e->name << ": the readings do not depend on the bias";
  }
}

TEST(Simulator, TemperatureReadingsLagTheBlockByTheSensorTimeConstant) {
  // On a steady ramp a first-order sensor reads T(t − τ): lag = τ·dT/dt.
  const Simulator sim = shipped("cycle");
  const ThermalTrace tr = sim.run_thermal();
  const double tau = sim.rig().sensor.time_constant_s;
  int checked = 0;
  for (std::size_t k = 0; k < tr.time_s.size(); k += 60) {
    const double rate = tr.anode_rate_c_per_s[k];
    if (std::abs(rate) < 5e-3) continue;
    const double lag = tr.node(N::anode)[k] - tr.node(N::sensor)[k];
    EXPECT_NEAR(lag, tau * rate, 0.1 * std::abs(tau * rate) + 2e-3) << "t " << tr.time_s[k];
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

}  // namespace
}  // namespace gyrotherm::sim
