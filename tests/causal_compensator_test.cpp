// The real-time compensator (fit/causal_compensator.h, `compensate --causal`):
// it uses nothing from the future, its windows are the fit's, and its glitch
// rule finds the glitches the offline rule finds.

#include "fit/causal_compensator.h"

#include <algorithm>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "fit/compensation.h"
#include "fit/pipeline.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

Measurement prefix(const Measurement& m, std::size_t n) {
  Measurement p = m;
  p.time_s.resize(n);
  p.temp_c.resize(n);
  p.gyro_dph.resize(n);
  if (!p.temp2_c.empty()) p.temp2_c.resize(n);
  for (auto& [name, values] : p.extra) values.resize(n);
  return p;
}

PipelineOptions causal(const SavedFit& fit) {
  PipelineOptions p = reading_columns_of(fit.pipeline, fit.terms);
  p.derivative = DerivativeMode::causal;
  return p;
}

// A record cut anywhere gives the same model up to the cut, for every term
// kind that looks back (rates, lag, hysteresis, warm-up, drift).
TEST(CausalCompensator, NothingFromTheFutureIsUsed) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  ASSERT_EQ(run_cli(dir, "fit c.csv --model 'T + T^2 + dT + d2T + T*dT + hyst + warmup + t + lag + grad' -o fit.json")
                .exit_code,
            0);
  const SavedFit fit = load_fit(dir / "fit.json");
  const Measurement m = read_measurement_csv(dir / "c.csv", causal(fit).columns);
  const Compensation whole = compensate(m, fit, causal(fit));
  for (const std::size_t cut : {std::size_t{50}, std::size_t{1234}, std::size_t{20000}}) {
    const Compensation part = compensate(prefix(m, cut), fit, causal(fit));
    for (std::size_t k = 0; k < cut; ++k) {
      ASSERT_EQ(part.model_dph[k], whole.model_dph[k]) << "cut " << cut << ", sample " << k;
      ASSERT_EQ(part.outlier[k], whole.outlier[k]) << "cut " << cut << ", sample " << k;
    }
  }
}

// Its windows are the offline pipeline's (same Δ, grid, fill rule), and at
// each window it gives the offline causal model; the sample after a window
// closes gets that window's bias.
TEST(CausalCompensator, WindowBiasesAreTheOfflineCausalModel) {
  ScratchDir dir;
  simulate_shipped(dir, "random", "", "r.csv");
  ASSERT_EQ(run_cli(dir, "fit r.csv --model 'T + T^2 + dT + lag' --causal --keep-outliers -o fit.json").exit_code, 0);
  const SavedFit fit = load_fit(dir / "fit.json");
  const Measurement m = read_measurement_csv(dir / "r.csv", causal(fit).columns);
  const PreparedData offline = prepare_data(m, causal(fit));
  const std::vector<double> model =
      model_values(design_matrix(offline.derived, fit.terms, fit.parameters), fit.coefficients);
  CausalSettings settings;
  settings.sample_interval_s = offline.averaging.sample_interval_s;
  CausalCompensator compensator(fit, settings);
  for (std::size_t k = 0; k < m.size(); ++k)
    compensator.update(m.time_s[k], m.temp_c[k], 0.0, m.gyro_dph[k], {}, nullptr);
  // Every window but one still open at the record's end (here the partial
  // last window, which the fill rule drops).
  ASSERT_GE(compensator.closed_windows() + 1, model.size());
  ASSERT_LE(compensator.closed_windows(), model.size());
  for (std::size_t p = 0; p < compensator.closed_windows(); ++p)
    ASSERT_NEAR(compensator.window_bias_dph()[p], model[p], 1e-12 * std::abs(model[p])) << "window " << p;
}

// Every term that looks back (rates, the second derivative, a rate under the
// sensor's time constant, hysteresis, a lag carried from window to window),
// with the temperature held within a range the record leaves: at every window
// exactly the offline causal model, though each window reads only the latest.
TEST(CausalCompensator, EveryTermThatLooksBackGivesTheOfflineModelExactly) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  ASSERT_EQ(run_cli(dir, "fit c.csv --model 'T + T^2 + dT + d2T + T*dT + hyst + lag + t' --causal --keep-outliers "
                         "--sensor-tau 120 -o fit.json")
                .exit_code,
            0);
  const SavedFit fit = load_fit(dir / "fit.json");
  const Measurement m = read_measurement_csv(dir / "c.csv", causal(fit).columns);
  const PreparedData offline = prepare_data(m, causal(fit));
  const auto [lo, hi] = std::minmax_element(offline.derived.temp_c.begin(), offline.derived.temp_c.end());
  CausalSettings settings;
  settings.sample_interval_s = offline.averaging.sample_interval_s;
  settings.hold_c = {*lo + 0.25 * (*hi - *lo), *hi - 0.25 * (*hi - *lo)};
  const std::vector<double> model = model_values(
      design_matrix_held(offline.derived, fit.terms, fit.parameters, settings.hold_c->first, settings.hold_c->second),
      fit.coefficients);
  CausalCompensator compensator(fit, settings);
  for (std::size_t k = 0; k < m.size(); ++k)
    compensator.update(m.time_s[k], m.temp_c[k], 0.0, m.gyro_dph[k], {}, nullptr);
  ASSERT_GE(compensator.closed_windows() + 1, model.size());
  ASSERT_GT(compensator.closed_windows(), 100u);
  for (std::size_t p = 0; p < compensator.closed_windows(); ++p)
    ASSERT_EQ(compensator.window_bias_dph()[p], model[p]) << "window " << p;
}

// The trailing glitch rule flags the same samples as the offline, centred one
// on a simulated record with counting glitches, with the fit's floor.
TEST(CausalCompensator, TheTrailingGlitchRuleFindsTheOfflineGlitches) {
  ScratchDir dir;
  simulate_shipped(dir, "random", "", "r.csv");
  ASSERT_EQ(run_cli(dir, "fit r.csv -o fit.json").exit_code, 0);
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "fit.json"));
  const SavedFit fit = load_fit(dir / "fit.json");
  ASSERT_TRUE(fit.outlier_floor_dph.has_value());
  const Measurement m = read_measurement_csv(dir / "r.csv", causal(fit).columns);
  const Compensation c = compensate(m, fit, causal(fit));
  std::vector<double> flagged;
  for (std::size_t k = 0; k < m.size(); ++k)
    if (c.outlier[k]) flagged.push_back(m.time_s[k]);
  const auto offline = j["data"]["outlier_times_s"].get<std::vector<double>>();
  ASSERT_GE(offline.size(), 5u);
  EXPECT_EQ(flagged, offline);
}

}  // namespace
}  // namespace gyrotherm::fit
