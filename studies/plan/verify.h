#pragma once
// `plan --verify N`: the planned test run N times by the simulator (seeds
// first, first + 1, …; the gyro's truth and noise), each record fitted as
// `gyrotherm fit --model … --engine ols` would (glitches removed, 100 s
// windows, the intervals from the record's identified noise), and set
// against the prediction:
//
//   achieved_se   the standard deviation of each coefficient over the seeds
//                 (n − 1 in the denominator): what the test delivers;
//   reported_se   the mean of the fits' own standard errors (their 95 %
//                 half-width / 1.96): what a user would be told;
//   coverage_95   how often the fit's 95 % interval holds the true value.
//
// The thermal trace does not depend on the seed: it is integrated once
// (sim::Simulator::record). Seeds run on two threads; the result does not
// depend on which thread ran which.

#include <cstdint>
#include <functional>
#include <vector>

#include "fit/model/terms.h"
#include "sim/gyro_config.h"
#include "sim/rig_config.h"
#include "sim/scenario.h"

namespace gyrotherm::studies::plan {

struct VerifyOutcome {
  std::vector<double> achieved_se, reported_se, coverage_95, truth, mean;  // per term
  int seeds = 0;
};

VerifyOutcome verify_plan(const sim::Scenario& scenario, const sim::RigConfig& rig, const sim::GyroConfig& gyro,
                          const std::vector<const fit::Term*>& terms, int seeds, std::uint64_t first_seed,
                          const std::function<void(int, int)>& progress = {});

}  // namespace gyrotherm::studies::plan
