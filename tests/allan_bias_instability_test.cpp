// allan's one bias-instability figure per series (studies/allan/series_noise.h):
// a flat part of the curve is a value only where the series' noise model
// accounts for it, else a bound; and a fit of several channels read with one
// gyro column each.

#include "studies/allan/series_noise.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;
using Json = nlohmann::json;

// The gate on a flat part (series_noise.h): a flat reading the series'
// noise model does not support becomes its 95 % bound; one it supports by
// a Gauss–Markov process stays; with flicker identified B is the model's
// floor, except on a plateau, where the curve's reading stays.
TEST(AllanStudy, AFlatPartIsBiasInstabilityOnlyWhereTheNoiseSupportsIt) {
  AllanCurve curve;
  curve.confidence = 0.683;
  curve.rows.push_back(AllanRow{});
  curve.rows.back().tau_s = 2048.0;
  curve.rows.back().edf = 16.0;
  curve.rows.back().adev_dph = 0.001;
  NoiseCoefficient flat;
  flat.shown = true;
  flat.method = CoefficientMethod::curve_flat;
  flat.value = 0.001 / kFlickerFloor;
  flat.lo = 0.8 * flat.value;
  flat.hi = 1.3 * flat.value;
  flat.tau_read_s = flat.tau_from_s = flat.tau_to_s = 2048.0;
  fit::NoiseModel white;
  white.amplitude[fit::kWhite] = 1.0;
  white.present[fit::kWhite] = white.identified[fit::kWhite] = true;

  NoiseCoefficient b = flat;
  EXPECT_EQ(settle_bias_instability(b, curve, white), BiasSupport::not_in_model);
  EXPECT_FALSE(b.shown);
  // The flat σ's 95 % upper value at 16 edf: σ·√(16/χ²₁₆(0.025)) = σ·√(16/6.908) = 1.522 σ.
  EXPECT_NEAR(b.upper_bound, 1.522 * flat.value, 0.002 * flat.value);
  b = flat;
  EXPECT_EQ(settle_bias_instability(b, curve, std::nullopt), BiasSupport::no_model);
  EXPECT_FALSE(b.shown);

  fit::NoiseModel gm = white;
  gm.amplitude[fit::kGaussMarkov] = 1e-6;
  gm.gm_tau_s = 1000.0;
  gm.present[fit::kGaussMarkov] = gm.identified[fit::kGaussMarkov] = true;
  b = flat;
  EXPECT_EQ(settle_bias_instability(b, curve, gm), BiasSupport::gauss_markov);
  EXPECT_TRUE(b.shown);
  EXPECT_DOUBLE_EQ(b.value, flat.value);

  fit::NoiseModel flicker = white;
  flicker.amplitude[fit::kFlicker] = 4e-8;
  flicker.flicker_tau_s = {100.0, 1000.0, 10000.0};
  flicker.flicker_floor_per_s = 2.0;
  flicker.covariance(1, 1) = std::pow(0.2 * 4e-8, 2);  // s² known to 20 %: ln B to 10 %
  flicker.present[fit::kFlicker] = flicker.identified[fit::kFlicker] = true;
  b = flat;
  EXPECT_EQ(settle_bias_instability(b, curve, flicker), BiasSupport::flicker);
  ASSERT_TRUE(b.shown);
  EXPECT_EQ(b.method, CoefficientMethod::noise_model);
  EXPECT_NEAR(b.value, 2.0 * 2e-4, 1e-12);
  EXPECT_NEAR(b.hi / b.value, std::exp(1.0 * 0.1), 0.002);  // the curve's 68.3 % confidence: z ≈ 1

  b = flat;
  b.plateau = true;
  EXPECT_EQ(settle_bias_instability(b, curve, flicker), BiasSupport::plateau);
  EXPECT_TRUE(b.shown);
  EXPECT_EQ(b.method, CoefficientMethod::curve_flat);
  b = flat;
  b.plateau = true;  // a plateau the model does not support (a compensation's leftover cycle, say)
  EXPECT_EQ(settle_bias_instability(b, curve, white), BiasSupport::not_in_model);
  EXPECT_FALSE(b.shown);
  // No flat part: the curve's bound stands (the model's would hold only if
  // its structure did).
  NoiseCoefficient none;
  none.method = CoefficientMethod::curve_flat;
  none.upper_bound = 1e-3;
  EXPECT_EQ(settle_bias_instability(none, curve, flicker), BiasSupport::no_flat_part);
  EXPECT_FALSE(none.shown);
  EXPECT_DOUBLE_EQ(none.upper_bound, 1e-3);
  // A plateau far above what the noise model gives there (its Allan
  // deviation at 2048 s is 0.022 °/h, the plateau's lower end 0.08): a
  // compensation's leftover cycle, say. Under flicker the model's floor is
  // the figure, not the hump; under a Gauss–Markov model alone, a bound.
  b = flat;
  b.plateau = true;
  b.value *= 100.0;
  b.lo *= 100.0;
  b.hi *= 100.0;
  const NoiseCoefficient hump = b;
  EXPECT_EQ(settle_bias_instability(b, curve, flicker), BiasSupport::flicker);
  EXPECT_EQ(b.method, CoefficientMethod::noise_model);
  EXPECT_NEAR(b.value, 4e-4, 1e-12);
  b = hump;
  EXPECT_EQ(settle_bias_instability(b, curve, gm), BiasSupport::not_in_model);
  EXPECT_FALSE(b.shown);
}

// A fit of two gyro columns: --gyro-col names one column per channel, in the
// fit's order (each channel's fit then reads its own); one column for two
// channels is refused, not read under both fits. The units line names the
// temperature column read, not the far-side one the fit also reads.
TEST(CliAllan, AFitOfSeveralChannelsTakesOneGyroColumnEach) {
  ScratchDir dir;
  std::string csv = "time_s,temp_c,temp2_c,gx,gy\n";
  for (int i = 0; i < 20000; ++i) {
    const double t = i, temp = 20.0 + 15.0 * std::sin(t / 3000.0), wobble = std::sin(0.7 * i) + std::cos(1.3 * i);
    csv += fmt::format("{},{:.4f},{:.4f},{:.6f},{:.6f}\n", t, temp, temp + 0.5, 0.02 * temp + wobble,
                       -0.01 * temp + 2.0 * std::sin(0.37 * i));
  }
  write_text(dir / "two.csv", csv);
  ASSERT_EQ(run_cli(dir, "fit two.csv --gyro-col gx,gy --model T -o two.json").exit_code, 0);
  const auto own = run_cli(dir, "allan two.csv --fit two.json --json");
  ASSERT_EQ(own.exit_code, 0) << own.err;
  const auto swapped = run_cli(dir, "allan two.csv --fit two.json --gyro-col gy,gx --json");
  ASSERT_EQ(swapped.exit_code, 0) << swapped.err;
  const Json a = Json::parse(own.out), b = Json::parse(swapped.out);
  ASSERT_EQ(a["channels"].size(), 2u);
  EXPECT_EQ(b["channels"][0]["series"][0]["adev_dph"], a["channels"][1]["series"][0]["adev_dph"]);
  EXPECT_EQ(b["channels"][1]["series"][0]["adev_dph"], a["channels"][0]["series"][0]["adev_dph"]);
  const auto one = run_cli(dir, "allan two.csv --fit two.json --gyro-col gx");
  EXPECT_EQ(one.exit_code, 2);
  EXPECT_NE(one.err.find("--gyro-col gx: 1 column for the 2 channels of two.json"), std::string::npos) << one.err;
  const auto text = run_cli(dir, "allan two.csv --fit two.json");
  EXPECT_NE(text.out.find("temperature C (header 'temp_c')"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("header 'temp2_c'"), std::string::npos) << text.out;
}

// Two temperature columns whose headers state different units are refused
// (exit 2, both named), whether the units come from the headers alone or a
// fit file brings its own (the header wins over it, once).
TEST(CliAllan, TemperatureColumnsInTwoUnitsAreRefused) {
  ScratchDir dir;
  std::string same = "time_s,temp (C),temp2 (C),gyro_dph\n", mixed = "time_s,temp (C),temp2 (K),gyro_dph\n";
  for (int i = 0; i < 4000; ++i) {
    const double temp = 20.0 + 15.0 * std::sin(i / 600.0), far = temp + 0.5 * std::sin(i / 97.0);
    const double gyro = 0.02 * temp + std::sin(0.7 * i);
    same += fmt::format("{},{:.4f},{:.4f},{:.6f}\n", i, temp, far, gyro);
    mixed += fmt::format("{},{:.4f},{:.4f},{:.6f}\n", i, temp, far + 273.15, gyro);
  }
  write_text(dir / "same.csv", same);
  write_text(dir / "mixed.csv", mixed);
  const std::string columns = " --temp-col 'temp (C)' --temp2-col 'temp2 (C)'";
  ASSERT_EQ(run_cli(dir, "fit same.csv --model 'T + grad'" + columns + " -o g.json").exit_code, 0);
  const auto plain = run_cli(dir, "allan mixed.csv --temp-col 'temp (C)' --temp2-col 'temp2 (K)'");
  const auto fitted = run_cli(dir, "allan mixed.csv --fit g.json --temp2-col 'temp2 (K)'");
  for (const auto& r : {plain, fitted}) {
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_NE(r.err.find("the temperature columns state different units (header 'temp (C)': C; 'temp2 (K)': K)"),
              std::string::npos)
        << r.err;
  }
}

}  // namespace
}  // namespace gyrotherm::studies
