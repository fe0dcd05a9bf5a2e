// lag (sim/effects/lag.cpp), the sensor-to-cavity thermal lag as a
// first-order filter: its regressor against the filter's analytic response,
// and the round trip: simulated with a hidden lag, `fit --add lag` recovers
// the coefficient and τ, `diagnose` ranks it first.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "studies/simulated.h"
#include "cli_runner.h"
#include "effect_round_trip.h"
#include "fit/model/formula.h"
#include "sim/config_loader.h"
#include "sim/effects/effect.h"
#include "sim/simulator.h"
#include "studies/diagnose/diagnosis.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;

// τ·y' = x − y, y(0) = x(0), for x rising at a °C/s from x0 until t1, then
// held: y = x − aτ(1 − e^{−t/τ}) on the ramp, then y = x1 − (x1 − y1)e^{−(t−t1)/τ}.
double ramp_and_hold(double t, double x0, double a, double t1, double tau) {
  if (t <= t1) return x0 + a * t - a * tau * (1.0 - std::exp(-t / tau));
  const double x1 = x0 + a * t1;
  const double y1 = x1 - a * tau * (1.0 - std::exp(-t1 / tau));
  return x1 - (x1 - y1) * std::exp(-(t - t1) / tau);
}

TEST(Lag, FollowsARampAndHoldExactlyOnAnyGrid) {
  const effects::Effect& lag = *effects::find("lag");
  constexpr double kTau = 900.0, kA = 0.01, kT1 = 3000.0;
  effects::EffectSeries s;
  // Irregular steps, a 20-minute gap, and a point at the corner t1.
  for (double t : {0.0, 50.0, 170.0, 400.0, 1000.0, 2200.0, 2950.0, 3000.0, 3100.0, 3500.0, 4700.0,
                   5000.0, 8000.0}) {
    s.time_s.push_back(t);
    s.temp_c.push_back(20.0 + kA * std::min(t, kT1));
  }
  const std::vector<double> y = effects::regressor_values(lag, s, kTau);
  for (std::size_t k = 0; k < y.size(); ++k)
    EXPECT_NEAR(y[k], ramp_and_hold(s.time_s[k], 20.0, kA, kT1, kTau), 1e-11) << "t " << s.time_s[k];
  // 5.6 τ after the ramp the cavity has nearly caught up; during it, it trails by aτ.
  EXPECT_GT(y.back(), 49.95);
  EXPECT_LT(y.back(), 50.0);
  EXPECT_NEAR(s.temp_c[6] - y[6], kA * kTau, 0.04 * kA * kTau);
}

TEST(Lag, IsListedAndInjectableFromTheCommandLine) {
  ScratchDir dir;
  const auto listed = run_cli(dir, "effects --json");
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  bool found = false;
  const auto listing = nlohmann::json::parse(listed.out);
  for (const auto& e : listing["effects"])
    if (e["term"] == "lag") {
      found = true;
      EXPECT_EQ(e["parameter"]["lower"].get<double>(), 60.0);
      EXPECT_EQ(e["parameter"]["upper"].get<double>(), 4.0 * 3600.0);
      EXPECT_EQ(e["parameter"]["gyro_key"], "lag_time_constant_s");
    }
  EXPECT_TRUE(found);

  // --hidden with the default τ, and a gyro file that sets τ.
  simulate_shipped(dir, "warmup", "--hidden lag=0.003", "a.csv");
  auto truth = nlohmann::json::parse(testing::slurp(dir / "a.truth.json"));
  EXPECT_EQ(truth["coefficients"]["lag"].get<double>(), 0.003);
  EXPECT_EQ(truth["hidden"]["lag"]["time_constant_s"].get<double>(), 1200.0);
  write_text(dir / "gyro.toml", "[hidden]\nlag = 0.004\nlag_time_constant_s = 900.0\n");
  simulate_shipped(dir, "warmup", "--gyro gyro.toml", "b.csv");
  truth = nlohmann::json::parse(testing::slurp(dir / "b.truth.json"));
  EXPECT_EQ(truth["coefficients"]["lag"].get<double>(), 0.004);
  EXPECT_EQ(truth["hidden"]["lag"]["time_constant_s"].get<double>(), 900.0);
  write_text(dir / "bad.toml", "[hidden]\nlag_time_constant_s = -5.0\n");
  const auto bad = run_cli(dir, "simulate " + source_path("scenarios/warmup.toml") + " --gyro bad.toml -o c.csv");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("lag_time_constant_s"), std::string::npos) << bad.err;
}

TEST(Lag, WorksEndToEnd) { expect_round_trip({.scenario = "cycle", .term = "lag", .coefficient = 0.003}); }

TEST(Lag, FitAddLagRecoversTau) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "--hidden lag=0.003", "lag.csv");
  const auto fit = run_cli(dir, "fit lag.csv --add lag --json");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const auto f = nlohmann::json::parse(fit.out);
  EXPECT_EQ(f["model"], "T + T^2 + dT + lag");
  const auto tau = f["parameter_intervals_95"]["lag"]["time_constant_s"];
  EXPECT_LE(tau[0].get<double>(), 1200.0);
  EXPECT_GE(tau[1].get<double>(), 1200.0);
  EXPECT_EQ(f["truth_parameters"]["lag"]["time_constant_s"].get<double>(), 1200.0);
  const auto diagnosis = run_cli(dir, "diagnose lag.csv --json");
  ASSERT_EQ(diagnosis.exit_code, 0) << diagnosis.err;
  EXPECT_NE(nlohmann::json::parse(diagnosis.out)["next_command"].get<std::string>().find("T + T^2 + dT + lag"),
            std::string::npos);
}

// Over seeds: the intervals of τ and of the coefficient (which carries τ's
// uncertainty, fit/pipeline.h) cover the truth as 95 % intervals should
// (12 of 12 seeds when this was written; held at 10), every estimate is
// within 20 %, and diagnose ranks lag first, significant, in every seed.
TEST(Lag, RecoveryOverSeeds) {
  sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  const sim::RigConfig rig = sim::load_rig(sc.rig_file);
  sim::GyroConfig gyro = sim::load_gyro(sc.gyro_file);
  gyro.coefficient["lag"] = 0.003;
  const sim::Simulator thermal(sc, rig, gyro);
  const sim::ThermalTrace trace = thermal.run_thermal();
  const auto with_lag = fit::parse_formula("T + T^2 + dT + lag");
  const fit::EngineInfo& ols = fit::find_engine("ols");
  int tau_covered = 0, c_covered = 0, first = 0;
  constexpr int kSeeds = 12;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    sc.seed = static_cast<std::uint64_t>(seed);
    const fit::PreparedData data = fit::prepare_data(
        studies::measurement_of(sim::Simulator(sc, rig, gyro).record(trace), "lag"), fit::PipelineOptions{});
    const fit::ModelFit f = fit::fit_model(data, with_lag, ols, {});
    EXPECT_NEAR(f.coefficients.b[3] / 0.003, 1.0, 0.2) << "seed " << seed;
    EXPECT_NEAR(f.parameters[3] / 1200.0, 1.0, 0.2) << "seed " << seed;
    c_covered += f.engine.inference.intervals[3].lower <= 0.003 && 0.003 <= f.engine.inference.intervals[3].upper;
    ASSERT_TRUE(f.parameter_intervals[3].has_value());
    tau_covered += f.parameter_intervals[3]->lower <= 1200.0 && 1200.0 <= f.parameter_intervals[3]->upper;
    const studies::Diagnosis d = studies::diagnose(data, fit::parse_formula("T + T^2 + dT"), ols, {});
    first += !d.candidates.empty() && d.candidates[0].term->name == "lag" && d.candidates[0].significant;
  }
  EXPECT_GE(tau_covered, 10) << "of " << kSeeds;
  EXPECT_GE(c_covered, 10) << "of " << kSeeds;
  EXPECT_EQ(first, kSeeds);
}

}  // namespace
}  // namespace gyrotherm
