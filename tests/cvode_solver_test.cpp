// CVODE on thermal networks whose solution is known in closed form:
//  - one node stepped in temperature: T(t) = T_b + (T_0 − T_b)·exp(−t G/C);
//  - a linear three-node network C dT/dt = −L T + s: the exact solution by the
//    eigen-decomposition of C^{-1/2} L C^{-1/2}, compared to 1e-6 K;
//  - the steady state with self-heating against the linear algebraic solution;
//  - a right-hand side that fails becomes a SolverError with CVODE's message.

#include "sim/cvode_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "sim/thermal_network.h"

namespace gyrotherm::sim {
namespace {

// A thermal network with constant node powers as an OdeSystem.
class NetworkOde : public OdeSystem {
 public:
  NetworkOde(const ThermalNetwork& net, std::vector<double> power)
      : net_(net), power_(std::move(power)) {}
  std::size_t size() const override { return net_.size(); }
  int rhs(double, std::span<const double> y, std::span<double> ydot) override {
    net_.rates(y, power_, ydot);
    return 0;
  }

 private:
  const ThermalNetwork& net_;
  std::vector<double> power_;
};

CvodeOptions tight() {
  CvodeOptions o;
  o.relative_tolerance = 1e-11;
  o.absolute_tolerance = {1e-11};
  return o;
}

// Integrates to each time in `times` (one step at a time, dense output).
std::vector<std::vector<double>> integrate(OdeSystem& ode, std::vector<double> y0,
                                           const std::vector<double>& times,
                                           const CvodeOptions& options = tight()) {
  CvodeSolver solver(ode, 0.0, y0, options);
  std::vector<std::vector<double>> out;
  const double end = times.back();
  std::vector<double> y(y0.size());
  for (double t : times) {
    while (solver.time() < t) solver.step_towards(end);
    solver.state_at(t, y);
    out.push_back(y);
  }
  return out;
}

TEST(CvodeSolver, OneNodeFollowsTheExponential) {
  ThermalNetwork net;
  const auto chamber = net.add_boundary("chamber");
  const auto block = net.add_node("block", 1000.0);
  net.conduct(block, chamber, 2.0);  // τ = 500 s
  NetworkOde ode(net, {0.0, 0.0});
  const std::vector<double> times = {10.0, 100.0, 500.0, 1000.0, 3000.0};
  const auto states = integrate(ode, {60.0, -40.0}, times);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double exact = 60.0 + (-40.0 - 60.0) * std::exp(-times[i] / 500.0);
    EXPECT_NEAR(states[i][block], exact, 1e-7) << "t = " << times[i];
    EXPECT_EQ(states[i][chamber], 60.0);
  }
}

// Three nodes in a chain to a boundary held at T_b, with powers: the exact
// solution of C Ṫ = −L (T − T_b) + P.
TEST(CvodeSolver, LinearThreeNodeNetworkMatchesEigenSolution) {
  const double tb = 23.0;
  const Eigen::Vector3d capacity(2500.0, 500.0, 800.0);
  const double g_case_room = 3.0, g_case_a = 0.4, g_a_b = 0.5, g_case_b = 0.6;
  const Eigen::Vector3d power(0.0, 1.15, 0.15);
  ThermalNetwork net;
  const auto room = net.add_boundary("room");
  const auto c = net.add_node("case", capacity[0]);
  const auto a = net.add_node("anode", capacity[1]);
  const auto b = net.add_node("far", capacity[2]);
  net.conduct(c, room, g_case_room);
  net.conduct(a, c, g_case_a);
  net.conduct(a, b, g_a_b);
  net.conduct(b, c, g_case_b);

  Eigen::Matrix3d L;
  L << g_case_room + g_case_a + g_case_b, -g_case_a, -g_case_b,  //
      -g_case_a, g_case_a + g_a_b, -g_a_b,                      //
      -g_case_b, -g_a_b, g_a_b + g_case_b;
  // u = T − T_b: C u̇ = −L u + P. With w = C^{1/2} u: ẇ = −A w + C^{-1/2} P,
  // A = C^{-1/2} L C^{-1/2} symmetric positive definite = V Λ Vᵀ.
  const Eigen::Vector3d s = capacity.cwiseSqrt();
  const Eigen::Matrix3d A = s.cwiseInverse().asDiagonal() * L * s.cwiseInverse().asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(A);
  ASSERT_EQ(eig.info(), Eigen::Success);
  const Eigen::Vector3d u0(-63.0, -63.0, -63.0);  // everything soaked at −40 °C
  const Eigen::Vector3d w0 = s.cwiseProduct(u0);
  const Eigen::Vector3d f = s.cwiseInverse().cwiseProduct(power);
  const Eigen::Matrix3d V = eig.eigenvectors();
  const Eigen::Vector3d lambda = eig.eigenvalues();
  const Eigen::Vector3d z0 = V.transpose() * w0, zf = V.transpose() * f;

  auto exact = [&](double t) {
    Eigen::Vector3d z;
    for (int i = 0; i < 3; ++i)
      z[i] = z0[i] * std::exp(-lambda[i] * t) + zf[i] / lambda[i] * (1.0 - std::exp(-lambda[i] * t));
    return Eigen::Vector3d(tb + (V * z).cwiseQuotient(s).array());
  };

  NetworkOde ode(net, {0.0, power[0], power[1], power[2]});
  const std::vector<double> times = {1.0, 60.0, 600.0, 3600.0, 4.0 * 3600.0, 20.0 * 3600.0};
  const auto states = integrate(ode, {tb, -40.0, -40.0, -40.0}, times);
  for (std::size_t k = 0; k < times.size(); ++k) {
    const Eigen::Vector3d e = exact(times[k]);
    EXPECT_NEAR(states[k][c], e[0], 1e-6) << "case at t = " << times[k];
    EXPECT_NEAR(states[k][a], e[1], 1e-6) << "anode at t = " << times[k];
    EXPECT_NEAR(states[k][b], e[2], 1e-6) << "far at t = " << times[k];
  }
}

TEST(CvodeSolver, SteadyStateWithSelfHeatingMatchesAlgebraicSolution) {
  // Same chain; at steady state L (T − T_b) = P.
  ThermalNetwork net;
  const auto room = net.add_boundary("room");
  const auto c = net.add_node("case", 18000.0);
  const auto a = net.add_node("anode", 500.0);
  const auto b = net.add_node("far", 500.0);
  net.conduct(c, room, 4.8);
  net.conduct(a, c, 0.4);
  net.conduct(a, b, 0.5);
  net.conduct(b, c, 0.6);
  const Eigen::Vector3d power(25.0, 1.15, 0.15);
  Eigen::Matrix3d L;
  L << 4.8 + 0.4 + 0.6, -0.4, -0.6, -0.4, 0.9, -0.5, -0.6, -0.5, 1.1;
  const Eigen::Vector3d steady = (L.ldlt().solve(power).array() + 23.0).matrix();

  NetworkOde ode(net, {0.0, power[0], power[1], power[2]});
  const auto states = integrate(ode, {23.0, 23.0, 23.0, 23.0}, {40.0 * 3600.0});
  EXPECT_NEAR(states[0][c], steady[0], 1e-6);
  EXPECT_NEAR(states[0][a], steady[1], 1e-6);
  EXPECT_NEAR(states[0][b], steady[2], 1e-6);
  // The self-heating makes a real gradient across the block.
  EXPECT_GT(states[0][a] - states[0][b], 0.5);
}

TEST(CvodeSolver, StepPolynomialEqualsCvodesDenseOutput) {
  ThermalNetwork net;
  const auto room = net.add_boundary("room");
  const auto a = net.add_node("a", 500.0);
  const auto b = net.add_node("b", 2000.0);
  net.conduct(a, b, 0.5);
  net.radiate(b, room, 0.8, 0.5);
  NetworkOde ode(net, {0.0, 1.0, 0.0});
  CvodeSolver solver(ode, 0.0, std::vector<double>{23.0, -40.0, 60.0});
  CvodeSolver::StepPolynomial poly;
  std::vector<double> y_poly(3), y_cvode(3);
  double t_prev = 0.0;
  int checked = 0;
  while (solver.time() < 20000.0) {
    const double t = solver.step_towards(20000.0);
    solver.step_polynomial(poly);
    for (double f : {0.0, 0.25, 0.5, 0.9, 1.0}) {
      const double tq = t_prev + f * (t - t_prev);
      poly.evaluate(tq, y_poly);
      solver.state_at(tq, y_cvode);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(y_poly[i], y_cvode[i], 1e-10) << tq;
      ++checked;
    }
    t_prev = t;
  }
  EXPECT_GT(checked, 50);
}

class FailingOde : public OdeSystem {
 public:
  std::size_t size() const override { return 1; }
  int rhs(double t, std::span<const double>, std::span<double> ydot) override {
    ydot[0] = 1.0;
    return t > 5.0 ? -1 : 0;
  }
};

TEST(CvodeSolver, UnrecoverableRhsFailureBecomesSolverError) {
  FailingOde ode;
  CvodeSolver solver(ode, 0.0, std::vector<double>{0.0});
  try {
    while (solver.time() < 100.0) solver.step_towards(100.0);
    FAIL() << "expected a SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("CV_RHSFUNC_FAIL"), std::string::npos) << e.what();
  }
}

TEST(CvodeSolver, StatisticsAccumulateAcrossRestarts) {
  ThermalNetwork net;
  const auto room = net.add_boundary("room");
  const auto n = net.add_node("n", 100.0);
  net.conduct(n, room, 1.0);
  NetworkOde ode(net, {0.0, 0.0});
  CvodeSolver solver(ode, 0.0, std::vector<double>{0.0, 50.0});
  while (solver.time() < 100.0) solver.step_towards(100.0);
  const SolverStatistics first = solver.statistics();
  EXPECT_GT(first.steps, 0);
  std::vector<double> y(2);
  solver.state_at(100.0, y);
  solver.restart(100.0, y);
  while (solver.time() < 200.0) solver.step_towards(200.0);
  const SolverStatistics both = solver.statistics();
  EXPECT_GT(both.steps, first.steps);
  EXPECT_GT(both.rhs_evaluations, first.rhs_evaluations);
  EXPECT_EQ(both.restarts, 1);
}

}  // namespace
}  // namespace gyrotherm::sim
