// The noise `gyrotherm plan` predicts with (studies/plan/plan_noise.h): a gyro
// file's noise is the simulator's (its Allan variance, and the covariance of
// the window means of records the simulator draws), a JSON's noise_model comes
// back with its components, and either is written to a gyro [noise] table
// that makes the simulator draw it.

#include "studies/plan/plan_noise.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "sim/util/gauss_markov.h"
#include "fit/fit_file.h"
#include "sim/config_loader.h"
#include "sim/noise.h"

namespace gyrotherm::studies::plan {
namespace {

using namespace gyrotherm::testing;
using fit::kFlicker;
using fit::kGaussMarkov;
using fit::kRandomWalk;
using fit::kWhite;

sim::NoiseConfig shipped_noise() { return sim::load_gyro(source_path("scenarios/gyro.toml")).noise; }

// The largest Allan deviation of the model's flicker bank (and Gauss–Markov
// process) over τ ≥ 1 s, on a grid of 2000 points per decade.
double flicker_floor(const fit::NoiseModel& model) {
  fit::NoiseModel flicker = model;
  flicker.amplitude[kWhite] = flicker.amplitude[kRandomWalk] = 0.0;
  double peak = 0.0;
  for (int k = 0; k <= 2000 * 9; ++k) peak = std::max(peak, flicker.allan_variance(std::pow(10.0, k / 2000.0)));
  return std::sqrt(peak);
}

double parameter(const fit::NoiseModel& model, const std::string& name) {
  for (const fit::NoiseParameter& p : model.parameters())
    if (p.name == name) return p.value;
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

TEST(PlanNoise, GyroFileNoiseHasTheSimulatorsAllanVariance) {
  sim::NoiseConfig config = shipped_noise();
  config.rrw_dph_per_sqrt_h = 2e-4;  // the shipped gyro has none
  const PlanNoise noise = noise_of_gyro(config, 1.0, "gyro file scenarios/gyro.toml");
  const sim::GyroNoise simulator(config, 1.0, 7);
  ASSERT_EQ(noise.model.flicker_tau_s, simulator.flicker_correlation_times_s());
  const double s2 = simulator.flicker_variance_dph2();
  const double n = config.arw_deg_per_sqrt_h, k = config.rrw_dph_per_sqrt_h;
  for (const double tau : {1.0, 10.0, 100.0, 1000.0, 1e4, 1e5}) {
    // IEEE 952: σ²(τ) = N²/τ_h (ARW, °/h with τ_h in hours) + the bank + K²τ_h/3.
    double avar = n * n / (tau / 3600.0) + k * k * (tau / 3600.0) / 3.0;
    for (const double t : simulator.flicker_correlation_times_s()) avar += sim::gauss_markov_allan_variance(s2, t, tau);
    EXPECT_NEAR(noise.model.allan_variance(tau) / avar, 1.0, 1e-9) << "tau " << tau;
  }
  EXPECT_NEAR(flicker_floor(noise.model) / config.bias_instability_dph, 1.0, 1e-5);
  // What NoiseModel reports (parameters(), description(), noise_model_json)
  // is the gyro file's.
  EXPECT_NEAR(parameter(noise.model, "arw"), n, 1e-15);
  EXPECT_NEAR(parameter(noise.model, "bias_instability") / config.bias_instability_dph, 1.0, 1e-12);
  EXPECT_NEAR(parameter(noise.model, "rrw") / k, 1.0, 1e-12);
  EXPECT_TRUE(noise.model.present[kWhite] && noise.model.present[kFlicker] && noise.model.present[kRandomWalk]);
  EXPECT_FALSE(noise.model.present[kGaussMarkov]);
  // Known, so not a bound (an absent component still reads "< 0 … (not pinned down)").
  EXPECT_NE(noise.model.description().find("bias_instability 0.0003 [0.0003, 0.0003] °/h"), std::string::npos)
      << noise.model.description();
  EXPECT_DOUBLE_EQ(noise.white_factor(config.arw_temp_ref_c + 10.0), std::pow(1.0 + 100.0 * 2e-4, 2));
  EXPECT_EQ(noise.description(),
            "white N = 2.7e-04 °/√h, flicker B = 3.0e-04 °/h (6 processes 10..20000 s), random walk K = 2.0e-04 "
            "°/h/√h, white ×(1 + 2e-04·(T − 20 °C)²)");
  EXPECT_EQ(noise_of_gyro(shipped_noise(), 1.0, "").description(),
            "white N = 2.7e-04 °/√h, flicker B = 3.0e-04 °/h (6 processes 10..20000 s), no random walk, "
            "white ×(1 + 2e-04·(T − 20 °C)²)");
}

// Window means of records the simulator draws (the shipped gyro's flicker
// bank alone) have the covariance NoiseModel::apply gives the model of the
// gyro file: 1500 records of 40 windows of 100 s, whitened by the model's
// Cholesky factor L (C = LLᵀ), give z = L⁻¹m with E[z zᵀ] = I. Checked: the
// mean square of z (1 ± 0.006 at 1σ), the mean product of neighbours (0 ±
// 0.004), and the variance of single windows, of neighbour sums and
// differences and of the record mean (each ± 3.7 % at 1σ). A bank 10 % too
// strong, or with its correlation times doubled, fails.
TEST(PlanNoise, SimulatedWindowMeansHaveTheModelsCovariance) {
  sim::NoiseConfig config = shipped_noise();
  config.arw_deg_per_sqrt_h = config.rrw_dph_per_sqrt_h = 0.0;
  config.quantization_arcsec = config.glitch_rate_per_h = 0.0;
  const PlanNoise noise = noise_of_gyro(config, 1.0, "flicker");
  constexpr int kWindows = 40, kRecords = 1500, kPerWindow = 100;
  fit::WindowGrid grid;
  grid.window_s = kPerWindow;
  for (int i = 0; i < kWindows; ++i) {
    grid.time_s.push_back(kPerWindow * (i + 0.5));  // sample k covers (k, k + 1] s
    grid.averaging_s.push_back(kPerWindow);
  }
  Eigen::MatrixXd means(kWindows, kRecords);
  for (int r = 0; r < kRecords; ++r) {
    sim::GyroNoise simulator(config, 1.0, static_cast<std::uint64_t>(1000 + r));
    for (int i = 0; i < kWindows; ++i) {
      double sum = 0.0;
      for (int k = 0; k < kPerWindow; ++k) sum += simulator.sample(0.0, 20.0);
      means(i, r) = sum / kPerWindow;
    }
  }

  // The statistics of `means` under `model`, in units of their standard errors.
  struct Deviations {
    double mean_square, neighbours, worst_variance;
  };
  const auto deviations = [&](const fit::NoiseModel& model) {
    const Eigen::MatrixXd c = model.apply(grid, Eigen::MatrixXd::Identity(kWindows, kWindows));
    const Eigen::LLT<Eigen::MatrixXd> llt(c);
    const Eigen::MatrixXd z = llt.matrixL().solve(means);
    Deviations d{};
    d.mean_square = (z.squaredNorm() / (kWindows * kRecords) - 1.0) / std::sqrt(2.0 / (kWindows * kRecords));
    const double products = (z.topRows(kWindows - 1).array() * z.bottomRows(kWindows - 1).array()).sum();
    d.neighbours = products / ((kWindows - 1) * kRecords) * std::sqrt((kWindows - 1.0) * kRecords);
    // wᵀm for a few w: its mean square against wᵀCw, in standard errors.
    // One window; two neighbours' sum and difference; the first and last; the record's mean.
    struct Pair {
      int i, j;
      double sign;
    };
    std::vector<Eigen::VectorXd> weights;
    for (const Pair p : {Pair{0, 0, 0.0}, Pair{20, 21, 1.0}, Pair{20, 21, -1.0}, Pair{0, 39, 1.0}}) {
      Eigen::VectorXd w = Eigen::VectorXd::Zero(kWindows);
      w[p.i] = 1.0;
      w[p.j] += p.sign;
      weights.push_back(w);
    }
    weights.push_back(Eigen::VectorXd::Constant(kWindows, 1.0 / kWindows));
    for (const Eigen::VectorXd& w : weights) {
      const double expected = w.dot(c * w);
      const Eigen::ArrayXd square = (w.transpose() * means).array().square();
      const double error = std::sqrt((square - square.mean()).square().sum() / (kRecords - 1.0) / kRecords);
      d.worst_variance = std::max(d.worst_variance, std::abs(square.mean() - expected) / error);
    }
    return d;
  };
  // Every statistic within 4 standard errors; printed when not.
  const auto agrees = [&](const fit::NoiseModel& model) {
    const Deviations d = deviations(model);
    const bool within = std::abs(d.mean_square) < 4.0 && std::abs(d.neighbours) < 4.0 && d.worst_variance < 4.0;
    return within ? ::testing::AssertionSuccess()
                  : ::testing::AssertionFailure() << "mean square " << d.mean_square << ", neighbours "
                                                  << d.neighbours << ", worst variance " << d.worst_variance
                                                  << " standard errors off";
  };
  EXPECT_TRUE(agrees(noise.model));  // -1.6, 0.4, 2.3
  // The same check fails a wrong model.
  fit::NoiseModel strong = noise.model;
  strong.amplitude[kFlicker] *= 1.1;
  EXPECT_FALSE(agrees(strong));  // mean square -17
  fit::NoiseModel slow = noise.model;
  for (double& tau : slow.flicker_tau_s) tau *= 2.0;
  EXPECT_FALSE(agrees(slow));  // mean square 7, neighbours -7, record mean's variance -8
}

// A file holding `json`, in dir.
std::filesystem::path json_file(const ScratchDir& dir, const std::string& name, const nlohmann::ordered_json& json) {
  const auto file = dir / name;
  write_text(file, json.dump(2));
  return file;
}

TEST(PlanNoise, FitJsonNoiseModelComesBackWithItsComponents) {
  const ScratchDir dir;
  // The noise_model fit --json writes for the shipped gyro's noise (+ a random walk).
  sim::NoiseConfig config = shipped_noise();
  config.rrw_dph_per_sqrt_h = 1e-4;
  const PlanNoise gyro = noise_of_gyro(config, 1.0, "gyro");
  const auto file = json_file(dir, "fit.json", {{"engine", "ols"}, {"noise_model", fit::noise_model_json(gyro.model)}});
  const PlanNoise noise = noise_of_json(file);
  EXPECT_EQ(noise.source, "noise_model of " + file.string());
  EXPECT_NEAR(std::sqrt(noise.model.amplitude[kWhite]) / 60.0, config.arw_deg_per_sqrt_h, 1e-15);
  EXPECT_NEAR(std::sqrt(noise.model.amplitude[kRandomWalk] * 3600.0), config.rrw_dph_per_sqrt_h, 1e-15);
  EXPECT_FALSE(noise.model.present[kGaussMarkov]);
  EXPECT_EQ(noise.arw_temp_coeff_per_c2, 0.0);
  // The bank: two per decade over 10..1e6 s, its floor B.
  ASSERT_EQ(noise.model.flicker_tau_s.size(), 11u);
  EXPECT_NEAR(noise.model.flicker_tau_s.front(), kJsonFlickerMinS, 1e-9);
  EXPECT_NEAR(noise.model.flicker_tau_s.back(), kJsonFlickerMaxS, 1e-3);
  EXPECT_NEAR(noise.model.flicker_tau_s[1] / noise.model.flicker_tau_s[0], std::sqrt(10.0), 1e-12);
  EXPECT_NEAR(flicker_floor(noise.model) / config.bias_instability_dph, 1.0, 1e-5);  // 1.5e-8
  EXPECT_NEAR(parameter(noise.model, "bias_instability") / config.bias_instability_dph, 1.0, 1e-12);
  EXPECT_EQ(noise.description(),
            "white N = 2.7e-04 °/√h, flicker B = 3.0e-04 °/h (11 processes 10..1e+06 s), random walk K = 1.0e-04 "
            "°/h/√h");
}

TEST(PlanNoise, AllanJsonTakesTheCompensatedSeries) {
  const ScratchDir dir;
  fit::NoiseModel raw, compensated;
  raw.amplitude[kWhite] = std::pow(60.0 * 5e-4, 2);
  raw.present[kWhite] = raw.identified[kWhite] = true;
  compensated.amplitude[kWhite] = std::pow(60.0 * 3e-4, 2);
  compensated.amplitude[kGaussMarkov] = 2e-3 * 2e-3;
  compensated.gm_tau_s = 3000.0;
  compensated.present = compensated.identified = {true, false, true, false};
  nlohmann::ordered_json allan = {
      {"series",
       {{{"name", "raw"}, {"noise_model", fit::noise_model_json(raw)}},
        {{"name", "compensated"}, {"noise_model", fit::noise_model_json(compensated)}}}}};
  const PlanNoise noise = noise_of_json(json_file(dir, "allan.json", allan));
  EXPECT_EQ(noise.source, "series 'compensated' noise_model of " + (dir / "allan.json").string());
  EXPECT_NEAR(std::sqrt(noise.model.amplitude[kWhite]) / 60.0, 3e-4, 1e-15);
  EXPECT_NEAR(noise.model.amplitude[kGaussMarkov], 4e-6, 1e-18);
  EXPECT_EQ(noise.model.gm_tau_s, 3000.0);
  EXPECT_FALSE(noise.model.present[kFlicker]);
  EXPECT_NEAR(noise.model.allan_variance(5000.0),
              std::pow(60.0 * 3e-4, 2) / 5000.0 + 4e-6 * gauss_markov_allan_shape(5000.0 / 3000.0), 1e-18);
  EXPECT_EQ(noise.description(),
            "white N = 3.0e-04 °/√h, no flicker, Gauss–Markov σ = 2.0e-03 °/h, τ = 3000 s, no random walk");
  // Without a compensated series: raw.
  allan["series"].erase(1);
  EXPECT_NEAR(std::sqrt(noise_of_json(json_file(dir, "raw.json", allan)).model.amplitude[kWhite]) / 60.0, 5e-4,
              1e-15);
}

// noise_config_of: the simulator, given the gyro file it writes, draws the
// flicker bank planned with (the same τ_i and s², so the same floor B), a
// Gauss–Markov process alone as a one-process bank of variance σ², and one
// beside a bank merged into it by its variance.
TEST(PlanNoise, WrittenNoiseMakesTheSimulatorDrawIt) {
  const ScratchDir dir;
  const auto components = [](double arw, double floor, double gm, double tau) {
    nlohmann::ordered_json c = {{"arw", {{"value", arw}}}, {"bias_instability", {{"value", floor}}},
                                {"gauss_markov", {{"value", gm}}}, {"rrw", {{"value", 0.0}}}};
    if (tau > 0.0) c["gauss_markov_tau"] = {{"value", tau}};
    return nlohmann::ordered_json{{"noise_model", {{"components", c}}}};
  };
  std::optional<GaussMarkovMerged> note = GaussMarkovMerged{};  // stale: each call resets it
  const PlanNoise flicker = noise_of_json(json_file(dir, "flicker.json", components(2e-4, 5e-4, 0.0, 0.0)));
  const sim::NoiseConfig written = noise_config_of(flicker, shipped_noise(), false, &note);
  EXPECT_FALSE(note);
  EXPECT_NEAR(written.arw_deg_per_sqrt_h, 2e-4, 1e-18);
  EXPECT_NEAR(written.bias_instability_dph, 5e-4, 1e-15);
  EXPECT_EQ(written.flicker_processes, 11);
  EXPECT_EQ(written.quantization_arcsec, 0.0);
  EXPECT_EQ(written.glitch_rate_per_h, 0.0);
  EXPECT_EQ(written.arw_temp_coeff_per_c2, 0.0);
  EXPECT_EQ(written.rrw_dph_per_sqrt_h, 0.0);
  // Read back as a gyro file's noise, it is the same model.
  const PlanNoise back = noise_of_gyro(written, 1.0, "written");
  ASSERT_EQ(back.model.flicker_tau_s.size(), flicker.model.flicker_tau_s.size());
  for (std::size_t i = 0; i < back.model.flicker_tau_s.size(); ++i)
    EXPECT_NEAR(back.model.flicker_tau_s[i] / flicker.model.flicker_tau_s[i], 1.0, 1e-12);
  EXPECT_NEAR(back.model.amplitude[kFlicker] / flicker.model.amplitude[kFlicker], 1.0, 1e-12);
  EXPECT_NEAR(flicker_floor(back.model) / 5e-4, 1.0, 1e-4);

  const PlanNoise gm = noise_of_json(json_file(dir, "gm.json", components(2e-4, 0.0, 2e-3, 700.0)));
  const sim::NoiseConfig one = noise_config_of(gm, shipped_noise(), false, &note);
  EXPECT_FALSE(note);
  EXPECT_EQ(one.flicker_processes, 1);
  const sim::GyroNoise simulator(one, 1.0, 3);
  ASSERT_EQ(simulator.flicker_correlation_times_s().size(), 1u);
  EXPECT_NEAR(simulator.flicker_correlation_times_s()[0], 700.0, 1e-9);
  EXPECT_NEAR(simulator.flicker_variance_dph2() / 4e-6, 1.0, 1e-12);

  const PlanNoise both = noise_of_json(json_file(dir, "both.json", components(2e-4, 5e-4, 2e-3, 700.0)));
  const sim::NoiseConfig merged = noise_config_of(both, shipped_noise(), false, &note);
  ASSERT_TRUE(note);
  EXPECT_NEAR(note->sigma_dph, 2e-3, 1e-15);  // the component's σ (°/h)
  EXPECT_EQ(note->tau_s, 700.0);
  EXPECT_EQ(note->processes, merged.flicker_processes);
  EXPECT_EQ(note->merged_b_dph, merged.bias_instability_dph);
  EXPECT_NE(note_text(*note).find("merged into the flicker bank"), std::string::npos) << note_text(*note);
  const sim::GyroNoise merged_simulator(merged, 1.0, 3);
  EXPECT_NEAR(merged_simulator.flicker_variance_dph2() / (both.model.amplitude[kFlicker] + 4e-6 / 11.0), 1.0, 1e-12);

  // From the gyro file itself: the file's own noise, quantisation and glitches included.
  const sim::NoiseConfig own =
      noise_config_of(noise_of_gyro(shipped_noise(), 1.0, "gyro"), shipped_noise(), true, &note);
  EXPECT_EQ(own.quantization_arcsec, shipped_noise().quantization_arcsec);
  EXPECT_EQ(own.glitch_rate_per_h, shipped_noise().glitch_rate_per_h);
  EXPECT_EQ(own.bias_instability_dph, shipped_noise().bias_instability_dph);
}

TEST(PlanNoise, BadJsonIsRefusedNamingTheFileAndField) {
  const ScratchDir dir;
  const auto file = dir / "bad.json";
  write_text(file, "{\"noise_model\": ");
  expect_input_error([&] { noise_of_json(file); }, {file.string(), "not valid JSON"});
  expect_input_error([&] { noise_of_json(dir / "absent.json"); }, {"absent.json", "no such file"});
  const auto with = [&](const nlohmann::ordered_json& j) { return json_file(dir, "bad.json", j); };
  expect_input_error([&] { noise_of_json(with({{"engine", "ols"}})); }, {file.string(), "no noise_model"});
  expect_input_error([&] { noise_of_json(with({{"noise_model", nullptr}})); },
                     {file.string(), "noise_model is null", "nothing to plan against"});
  expect_input_error([&] { noise_of_json(with({{"noise_model", {{"method", "REML"}}}})); },
                     {file.string(), "noise_model.components: missing (an object {arw, bias_instability"});
  expect_input_error([&] { noise_of_json(with({{"noise_model", {{"components", 3}}}})); },
                     {file.string(), "noise_model.components: expected an object {arw, bias_instability"});
  expect_input_error([&] { noise_of_json(with({{"noise_model", {{"components", {{"rrw", 2}}}}}})); },
                     {file.string(), "noise_model.components.rrw = 2: expected {\"value\": a number >= 0 in °/h/√h"});
  const auto arw = [&](const nlohmann::ordered_json& value) {
    return with({{"noise_model", {{"components", {{"arw", {{"value", value}}}}}}}});
  };
  expect_input_error([&] { noise_of_json(arw(-1e-4)); },
                     {file.string(), "noise_model.components.arw.value = -0.0001", "expected a number >= 0 (°/√h)"});
  expect_input_error([&] { noise_of_json(arw("3e-4")); },
                     {file.string(), "noise_model.components.arw.value = \"3e-4\"", "expected a number >= 0"});
  expect_input_error([&] { noise_of_json(arw(0.0)); },
                     {"the noise model of " + file.string() + " has no component: nothing to plan against"});
  expect_input_error(
      [&] { noise_of_json(with({{"noise_model", {{"components", {{"gauss_markov", {{"value", 1e-3}}}}}}}})); },
      {file.string(), "noise_model.components.gauss_markov_tau.value", "correlation time (s, > 0)"});
  expect_input_error(
      [&] {
        noise_of_json(with({{"series", {{{"name", "raw"}, {"noise_model", {{"components", {}}}}},
                                         {{"name", "compensated"}, {"noise_model", nullptr}}}}}));
      },
      {file.string(), "series[1].noise_model is null", "series 'compensated' was too short"});
  expect_input_error([&] { noise_of_json(with({{"channels", {{{"channel", "gx"}}, {{"channel", "gy"}}}}})); },
                     {file.string(), "holds 2 channels (gx, gy)", "--gyro-col"});
}

}  // namespace
}  // namespace gyrotherm::studies::plan
