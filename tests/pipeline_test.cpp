// The pipeline on simulated data: variable projection recovers a hidden
// turn-on transient's time constant; adding a missing effect lowers the
// instability; a term without its column is refused.

#include "studies/simulated.h"
#include "fit/pipeline.h"

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "fit/model/formula.h"
#include "fit/engines/ols.h"
#include "sim/config_loader.h"
#include "sim/util/input_error.h"
#include "sim/simulator.h"

namespace gyrotherm::fit {
namespace {

using gyrotherm::testing::source_path;

PreparedData simulate_cycle(sim::GyroConfig gyro, std::uint64_t seed = 1) {
  sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  sc.seed = seed;
  const sim::SimulationResult r = sim::Simulator(sc, sim::load_rig(sc.rig_file), gyro).run();
  const Measurement m = studies::measurement_of(r, "cycle");
  return prepare_data(m, PipelineOptions{});
}

sim::GyroConfig shipped_gyro() {
  return sim::load_gyro(source_path("scenarios/gyro.toml"));
}

TEST(Pipeline, VariableProjectionRecoversAWarmUpTimeConstant) {
  sim::GyroConfig gyro = shipped_gyro();
  gyro.coefficient["warmup"] = 0.02;  // °/h at switch-on
  gyro.parameter["warmup"] = 2400.0;  // τ, s
  const PreparedData data = simulate_cycle(gyro);
  const auto terms = parse_formula("T + T^2 + dT + warmup");
  const ModelFit fit = fit_model(data, terms, find_engine("ols"), {});
  // The search does its job: the chosen τ fits at least as well as the true one.
  std::vector<double> at_truth = fit.parameters;
  at_truth[3] = 2400.0;
  const Eigen::VectorXd y = Eigen::Map<const Eigen::VectorXd>(data.series.gyro_dph.data(),
                                                              static_cast<Eigen::Index>(data.series.size()));
  const LinearProblem truth_problem(design_matrix(data.derived, terms, at_truth), y,
                                    {"T", "T^2", "dT", "warmup"});
  EXPECT_LE(fit.optimum_dph, truth_problem.sigma_two_pass(truth_problem.physical(
                                 least_squares_optimum(truth_problem))) * (1.0 + 1e-9));
  // And recovers the physics, within what the flicker on the same time scale allows.
  EXPECT_NEAR(fit.parameters[3] / 2400.0, 1.0, 0.35);
  EXPECT_NEAR(fit.coefficients.b[3] / 0.02, 1.0, 0.25);
  const ModelFit without = fit_model(data, parse_formula("T + T^2 + dT"), find_engine("ols"), {});
  EXPECT_LT(fit.instability_after_dph, 0.8 * without.instability_after_dph);
}

// The linearised 95 % interval of a nonlinear parameter (a hidden warm-up,
// τ = 2400 s) covers the truth in most seeds. Not in 95 % of them: like the
// coefficients' ols intervals it cannot see the gyro's flicker, whose memory
// is as long as the cycle (results/ols_coverage.md); measured here, 15 of 20
// and 32 of 40 seeds. A dead band, where the regressor jumps, gets none.
TEST(Pipeline, ParameterIntervalsCoverTheTruth) {
  sim::GyroConfig gyro = shipped_gyro();
  gyro.coefficient["warmup"] = 0.02;
  gyro.parameter["warmup"] = 2400.0;
  const auto terms = parse_formula("T + T^2 + dT + warmup");
  int covered = 0;
  constexpr int kSeeds = 20;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const ModelFit fit = fit_model(simulate_cycle(gyro, seed), terms, find_engine("ols"), {});
    ASSERT_TRUE(fit.parameter_intervals[3].has_value()) << "seed " << seed;
    const Interval& i = *fit.parameter_intervals[3];
    EXPECT_LT(i.lower, fit.parameters[3]);
    EXPECT_GT(i.upper, fit.parameters[3]);
    // The identified noise's slow power is in the interval (wider than the
    // kernel estimators' were): still within a factor of ~2.2 either way.
    EXPECT_LT(i.upper / i.lower, 5.0) << "an interval that says nothing";
    covered += i.lower <= 2400.0 && 2400.0 <= i.upper;
    for (std::size_t j = 0; j < 3; ++j) EXPECT_FALSE(fit.parameter_intervals[j].has_value());
  }
  EXPECT_GE(covered, 13) << "of " << kSeeds;
  // Without ols there are no intervals at all.
  EngineSettings settings;
  settings.seed = 1;
  const ModelFit swarm = fit_model(simulate_cycle(gyro, 1), terms, find_engine("iafsa"), settings);
  EXPECT_FALSE(swarm.parameter_intervals[3].has_value());
  // hyst's dead band: no linearised interval.
  sim::GyroConfig h = shipped_gyro();
  h.coefficient["hyst"] = 0.003;
  const ModelFit with_hyst =
      fit_model(simulate_cycle(h, 1), parse_formula("T + T^2 + dT + hyst"), find_engine("ols"), {});
  EXPECT_FALSE(with_hyst.parameter_intervals[3].has_value());
}

TEST(Pipeline, AddingAHiddenGradientLowersTheInstability) {
  sim::GyroConfig gyro = shipped_gyro();
  gyro.coefficient["grad"] = 0.03;
  const PreparedData data = simulate_cycle(gyro);
  const ModelFit with = fit_model(data, parse_formula("T + T^2 + dT + grad"), find_engine("ols"), {});
  const ModelFit without = fit_model(data, parse_formula("T + T^2 + dT"), find_engine("ols"), {});
  EXPECT_LT(with.instability_after_dph, without.instability_after_dph);
  EXPECT_NEAR(with.coefficients.b[3] / 0.03, 1.0, 0.3);
}

TEST(Pipeline, GlitchesAreRemovedAndReported) {
  sim::GyroConfig gyro = shipped_gyro();
  gyro.noise.glitch_rate_per_h = 5.0;
  const PreparedData data = simulate_cycle(gyro);
  // 8.8 h at 5 per hour: about 44 glitches, each ±2 °/h, all found.
  EXPECT_GT(data.outliers.removed, 25u);
  EXPECT_LT(data.outliers.removed, 70u);
  EXPECT_EQ(data.outliers.times_s.size(), data.outliers.removed);
}

TEST(Pipeline, TermWithoutItsColumnIsRefused) {
  sim::GyroConfig gyro = shipped_gyro();
  PreparedData data = simulate_cycle(gyro);
  data.series.temp2_c.clear();
  try {
    check_columns(parse_formula("T + grad"), data, ColumnMap{});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("needs the column 'temp2_c'"), std::string::npos);
  }
}

}  // namespace
}  // namespace gyrotherm::fit
