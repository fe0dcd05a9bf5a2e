#pragma once
// Synthetic fitting problems for the engine tests: a smooth −40..60 °C
// temperature cycle sampled as 100 s windows, the paper's regressors
// (T, T², dT/dt by central differences) and y from known coefficients, with
// optional white or AR(1) noise from a fixed seed.

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "fit/data/averaging.h"
#include "fit/model/formula.h"
#include "fit/model/linear_problem.h"
#include "fit/pipeline.h"

namespace gyrotherm::testing {

// The paper's coefficients.
inline constexpr double kB0 = -7.07712, kB1 = -3.05e-4, kB2 = 1.06e-6, kB3 = 1.81;

// A cycle like the shipped one, as a gyro lagging the chamber: T(t) smooth.
inline fit::AveragedSeries synthetic_cycle(std::size_t windows = 320, double window_s = 100.0) {
  fit::AveragedSeries s;
  s.start_time_s = 0.0;
  for (std::size_t p = 0; p < windows; ++p) {
    const double t = (static_cast<double>(p) + 0.5) * window_s;
    const double phase = 2.0 * M_PI * t / (static_cast<double>(windows) * window_s / 1.5);
    s.time_s.push_back(t);
    s.temp_c.push_back(10.0 + 50.0 * std::sin(phase) * std::tanh(3.0 * std::cos(0.37 * phase) + 0.5) +
                       4.0 * std::sin(2.3 * phase));
    s.gyro_dph.push_back(0.0);
    s.samples.push_back(static_cast<std::size_t>(window_s));
    s.run.push_back(0);
  }
  return s;
}

// y = b0 + b1 T + b2 T² + b3 dT/dt (+ noise σ, AR(1) with coefficient rho).
inline fit::LinearProblem paper_problem(double noise_dph = 0.0, double rho = 0.0,
                                        std::uint64_t seed = 1, std::size_t windows = 320) {
  fit::AveragedSeries s = synthetic_cycle(windows);
  const fit::DerivedSeries d = fit::derive(s, fit::DerivativeMode::central);
  const std::vector<const fit::Term*> terms = fit::parse_formula("T + T^2 + dT");
  const Eigen::MatrixXd x = fit::design_matrix(d, terms, fit::default_parameters(terms));
  boost::random::mt19937_64 rng(seed);
  boost::random::normal_distribution<double> normal;
  Eigen::VectorXd y(x.rows());
  double e = 0.0;
  for (Eigen::Index p = 0; p < x.rows(); ++p) {
    e = rho * e + std::sqrt(1.0 - rho * rho) * noise_dph * normal(rng);
    y[p] = kB0 + kB1 * x(p, 0) + kB2 * x(p, 1) + kB3 * x(p, 2) + e;
  }
  return fit::LinearProblem(x, y, {"T", "T^2", "dT"});
}

}  // namespace gyrotherm::testing
