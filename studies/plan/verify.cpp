#include "studies/plan/verify.h"

#include <algorithm>
#include <cmath>

#include "fit/pipeline.h"
#include "sim/simulator.h"
#include "sim/util/parallel_for.h"
#include "studies/simulated.h"
#include "sim/util/numbers.h"

namespace gyrotherm::studies::plan {

namespace {


struct SeedFit {
  std::vector<double> b, lower, upper;
};

}  // namespace

VerifyOutcome verify_plan(const sim::Scenario& scenario, const sim::RigConfig& rig, const sim::GyroConfig& gyro,
                          const std::vector<const fit::Term*>& terms, int seeds, std::uint64_t first_seed,
                          const std::function<void(int, int)>& progress) {
  const sim::ThermalTrace trace = sim::Simulator(scenario, rig, gyro).run_thermal();
  std::vector<SeedFit> fits(static_cast<std::size_t>(seeds));
  parallel_for(
      fits.size(), threads_at_most(2),
      [&](std::size_t k) {
        sim::Scenario sc = scenario;
        sc.seed = first_seed + k;
        const fit::Measurement m = measurement_of(sim::Simulator(sc, rig, gyro).record(trace), scenario.name);
        const fit::ModelFit f = fit::reference_fit(fit::prepare_data(m, {}), terms);
        SeedFit& s = fits[k];
        s.b = f.coefficients.b;
        for (const fit::Interval& iv : f.engine.inference.intervals) {
          s.lower.push_back(iv.lower);
          s.upper.push_back(iv.upper);
        }
      },
      [&](std::size_t done) {
        if (progress) progress(static_cast<int>(done), seeds);
      });

  VerifyOutcome out;
  out.seeds = seeds;
  const std::size_t m = terms.size();
  for (std::size_t j = 0; j < m; ++j) {
    const double truth = terms[j]->effect ? gyro.coefficient_of(*terms[j]->effect) : 0.0;
    double sum = 0.0, sum2 = 0.0, reported = 0.0;
    int covered = 0, with_interval = 0;
    for (const SeedFit& s : fits) sum += s.b[j];
    const double mean = sum / seeds;
    for (const SeedFit& s : fits) {
      sum2 += (s.b[j] - mean) * (s.b[j] - mean);
      if (j < s.lower.size()) {
        ++with_interval;
        covered += s.lower[j] <= truth && truth <= s.upper[j];
        reported += 0.5 * (s.upper[j] - s.lower[j]) / kZ95;
      }
    }
    out.truth.push_back(truth);
    out.mean.push_back(mean);
    out.achieved_se.push_back(seeds > 1 ? std::sqrt(sum2 / (seeds - 1)) : 0.0);
    out.reported_se.push_back(with_interval ? reported / with_interval : std::nan(""));
    out.coverage_95.push_back(with_interval ? static_cast<double>(covered) / with_interval : std::nan(""));
  }
  return out;
}

}  // namespace gyrotherm::studies::plan
