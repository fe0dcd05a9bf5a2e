#pragma once
// How often the 95 % intervals of a fit hold the true coefficients, over
// seeds of a simulated scenario with a chosen noise: the check that an
// interval means what it says under the record's own (coloured) noise.

#include <cstdint>
#include <string>
#include <vector>

#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/scenario.h"

namespace gyrotherm::studies {

// The noise variants of the study, by name: white, white+flicker (the default
// gyro), flicker, white+gm1000, white+gm3600, white+rrw. Throws
// std::invalid_argument for another name.
sim::NoiseConfig noise_variant(const std::string& name, sim::NoiseConfig base);
const std::vector<std::string>& noise_variant_names();

struct CoverageOptions {
  std::string model = "T + T^2 + dT";
  std::string intervals = "model";  // ols's intervals option (the one-method form below)
  int seeds = 100;
  std::uint64_t first_seed = 1;
};

// One way of fitting each simulated record: an engine, its intervals option
// (empty: the engine's default) and the temperature sensor's time constant
// the pipeline de-lags by (--sensor-tau; 0: none).
struct CoverageMethod {
  std::string engine = "ols";
  std::string intervals;
  double sensor_tau_s = 0.0;
};

struct TermCoverage {
  std::string term;
  double truth = 0;
  int covered = 0;
  double bias = 0, sd = 0;   // of the relative error over the seeds
  double half_width = 0;     // mean relative half-width of the interval
};

struct Coverage {
  int seeds = 0;
  std::vector<TermCoverage> terms;  // the model's terms whose truth is not 0
};

// Simulates `scenario` with `gyro` for seeds first_seed.., fits the model
// with ols and counts the intervals that hold the truth.
Coverage interval_coverage(const sim::Scenario& scenario, const sim::RigConfig& rig,
                           const sim::GyroConfig& gyro, const CoverageOptions& options);
// The same for several methods on the same records (each simulated once): one
// Coverage per method, in order.
std::vector<Coverage> interval_coverage(const sim::Scenario& scenario, const sim::RigConfig& rig,
                                        const sim::GyroConfig& gyro, const CoverageOptions& options,
                                        const std::vector<CoverageMethod>& methods);

}  // namespace gyrotherm::studies
