#pragma once
// The synthetic problem the swarm-engine tests (afsa_test.cpp, iafsa_test.cpp)
// share: the paper's bias model on a −40..60 °C cycle seen through a
// first-order lag, in 3- and 6-term designs, with its exact least-squares σ
// from an Eigen QR computed here (never from an engine).

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <boost/random/normal_distribution.hpp>

#include "fit/engines/engine.h"
#include "fit/model/linear_problem.h"
#include "sim/util/input_error.h"
#include "sim/util/random.h"

namespace gyrotherm::testing::lagged_cycle {

using fit::FitResult;
using fit::LinearProblem;

// The paper's training test (section 3.2) in outline: the chamber soaks 2 h
// at 20 °C, then ramps at 5 °C/min to 60, −40 and 60 °C with a 2 h soak at
// each end. Piecewise linear in t.
inline double chamber_c(double t_s) {
  const double rate_c_per_s = 5.0 / 60.0;
  std::vector<std::pair<double, double>> knots = {{0.0, 20.0}, {7200.0, 20.0}};
  for (const double level_c : {60.0, -40.0, 60.0}) {
    const auto [t0, c0] = knots.back();
    const double t1 = t0 + std::abs(level_c - c0) / rate_c_per_s;
    knots.push_back({t1, level_c});
    knots.push_back({t1 + 7200.0, level_c});
  }
  for (std::size_t k = 1; k < knots.size(); ++k)
    if (t_s <= knots[k].first) {
      const auto [t0, c0] = knots[k - 1];
      const auto [t1, c1] = knots[k];
      return t1 > t0 ? c0 + (c1 - c0) * (t_s - t0) / (t1 - t0) : c1;
    }
  return knots.back().second;
}

// l = 300 points 100 s apart. The gyro sensor follows the chamber through a
// first-order lag (τ = 20 min), a second sensor on the far side with τ = 30
// min; dT/dt (°C/s) is the lag's own derivative (chamber − T)/τ, so T, T² and
// dT/dt are correlated as on a real cycle.
struct Cycle {
  Eigen::MatrixXd design;
  std::vector<std::string> names;
};

inline Cycle cycle_design(bool six_terms) {
  const int l = 300;
  const double spacing_s = 100.0, tau_s = 1200.0, tau2_s = 1800.0;
  Eigen::VectorXd t_c(l), dt_c_per_s(l), t2_c(l);
  double temp_c = 20.0, temp2_c = 20.0;
  for (int p = 0; p < l; ++p) {
    const double t_s = p * spacing_s;
    if (p > 0)
      for (double s = t_s - spacing_s; s < t_s; s += 1.0) {
        temp_c += (1.0 - std::exp(-1.0 / tau_s)) * (chamber_c(s) - temp_c);
        temp2_c += (1.0 - std::exp(-1.0 / tau2_s)) * (chamber_c(s) - temp2_c);
      }
    t_c[p] = temp_c;
    dt_c_per_s[p] = (chamber_c(t_s) - temp_c) / tau_s;
    t2_c[p] = temp2_c;
  }
  Cycle c;
  const Eigen::VectorXd t_sq = t_c.array().square();
  if (!six_terms) {
    c.design.resize(l, 3);
    c.design << t_c, t_sq, dt_c_per_s;
    c.names = {"T", "T^2", "dT"};
  } else {
    c.design.resize(l, 6);
    c.design << t_c, t_sq, t_c.array().cube().matrix(), dt_c_per_s,
        (t_c.array() * dt_c_per_s.array()).matrix(), t2_c - t_c;
    c.names = {"T", "T^2", "T^3", "dT", "T*dT", "grad"};
  }
  return c;
}

// The paper's model B = −7.07712 − 3.05e−4·T + 1.06e−6·T² + 1.81·dT/dt (°/h),
// extended for the 6-term design, plus white noise of noise_dph on each
// 100 s average.
inline constexpr double kIntercept = -7.07712;
inline const std::vector<double> kPaper = {-3.05e-4, 1.06e-6, 1.81};
inline const std::vector<double> kSixTerm = {-3.05e-4, 1.06e-6, 2.0e-9, 1.81, -5.0e-3, 0.02};

inline Eigen::VectorXd bias_dph(const Eigen::MatrixXd& design, const std::vector<double>& b,
                         double noise_dph) {
  Rng rng = make_rng(42, 1);
  boost::random::normal_distribution<double> noise(0.0, noise_dph > 0.0 ? noise_dph : 1.0);
  Eigen::VectorXd y(design.rows());
  for (Eigen::Index p = 0; p < design.rows(); ++p) {
    y[p] = kIntercept + (noise_dph > 0.0 ? noise(rng) : 0.0);
    for (Eigen::Index j = 0; j < design.cols(); ++j)
      y[p] += b[static_cast<std::size_t>(j)] * design(p, j);
  }
  return y;
}

// The exact least-squares optimum of y = b0 + X b: QR of the centred,
// scaled design, then σ of the residuals (two-pass, l − 1).
inline double least_squares_sigma(const Eigen::MatrixXd& design, const Eigen::VectorXd& y) {
  const double dof = static_cast<double>(design.rows() - 1);
  Eigen::MatrixXd x = design.rowwise() - design.colwise().mean();
  for (Eigen::Index j = 0; j < x.cols(); ++j) x.col(j) /= std::sqrt(x.col(j).squaredNorm() / dof);
  const Eigen::VectorXd yc = y.array() - y.mean();
  const Eigen::VectorXd beta = x.colPivHouseholderQr().solve(yc);
  const Eigen::VectorXd r = yc - x * beta;
  return std::sqrt((r.array() - r.mean()).square().sum() / dof);
}

inline LinearProblem make_problem(const Cycle& c, const Eigen::VectorXd& y) {
  return LinearProblem(c.design, y, c.names);
}

// σ of the residuals at the engine's answer, recomputed from the data.
inline double sigma_at(const LinearProblem& problem, const FitResult& r) {
  return problem.sigma_two_pass(problem.physical(r.z));
}

// An engine at its defaults (default budget, no target) on the paper's cycle
// with 0.002 °/h of noise, once per seed 1..5; each run is checked against
// `optimum` by the caller.
struct DefaultRuns {
  LinearProblem problem;
  double optimum;  // the least-squares σ
  std::vector<FitResult> runs;
};

inline DefaultRuns runs_at_defaults(const std::string& engine) {
  const Cycle c = cycle_design(false);
  const Eigen::VectorXd y = bias_dph(c.design, kPaper, 0.002);
  DefaultRuns d{make_problem(c, y), least_squares_sigma(c.design, y), {}};
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    fit::EngineSettings settings;
    settings.seed = seed;
    d.runs.push_back(fit::find_engine(engine).make(settings)->fit(d.problem));
  }
  return d;
}

// σ at the engine's answer within `relative` above the optimum, and not below it.
inline void expect_near_optimum(const DefaultRuns& d, const FitResult& r, double relative) {
  EXPECT_LE(r.objective, d.optimum * (1.0 + relative));
  EXPECT_LE(sigma_at(d.problem, r), d.optimum * (1.0 + relative));
  EXPECT_GE(sigma_at(d.problem, r), d.optimum * (1.0 - 1e-12));
}

// The engine at its defaults on noise-free data of the paper's model: the
// coefficients within `relative`, the intercept within `relative_b0`.
inline void expect_recovers_noise_free(const std::string& engine, double relative, double relative_b0) {
  const Cycle c = cycle_design(false);
  const LinearProblem problem = make_problem(c, bias_dph(c.design, kPaper, 0.0));
  const FitResult r = fit::find_engine(engine).make(fit::EngineSettings{})->fit(problem);
  const fit::Coefficients fitted = problem.physical(r.z);
  for (std::size_t j = 0; j < kPaper.size(); ++j)
    EXPECT_NEAR(fitted.b[j], kPaper[j], relative * std::abs(kPaper[j])) << c.names[j];
  EXPECT_NEAR(fitted.intercept, kIntercept, relative_b0 * std::abs(kIntercept));
}

// The six correlated terms (condition number ≈ 400) with 0.002 °/h of noise,
// and their least-squares σ.
struct SixTermProblem {
  LinearProblem problem;
  double optimum;
};
inline SixTermProblem six_term_problem() {
  const Cycle c = cycle_design(true);
  const Eigen::VectorXd y = bias_dph(c.design, kSixTerm, 0.002);
  return {make_problem(c, y), least_squares_sigma(c.design, y)};
}

// An engine built from an Options aggregate checks it with its option table
// and the stopping rules: `bad` must be refused with `message`; the defaults,
// a negative budget and a negative target are checked too.
template <class EngineT>
void expect_aggregate_checked(const typename EngineT::Options& bad, const std::string& message) {
  using Options = typename EngineT::Options;
  const auto refused = [](const Options& o, const std::string& fragment) {
    try {
      EngineT{o};
      ADD_FAILURE() << fragment << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  refused(bad, message);
  EXPECT_NO_THROW(Options{}.validate());
  refused(Options{.max_evaluations = -5}, "max_evaluations=-5: must be at least 1");
  refused(Options{.target_objective = -1.0}, "target_objective=-1");
}

}  // namespace gyrotherm::testing::lagged_cycle
