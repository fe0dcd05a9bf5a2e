// A short real-like thermal sweep as a MEMS IMU logs it (issue 37): 70 min at
// 2 Hz, tab-separated, µs timestamps, cooling from 52 to −18 °C, heating to
// 74 °C and cooling again, the gyro's die lagging the temperature sensor by a
// first-order lag the paper's model does not have, at 20 × the noise floor,
// and the log's other channels (accelerometers, the other gyro axes, a status
// word) named with dots. The hidden lag must be named first and significant;
// the other channels are not candidates.

#include <gtest/gtest.h>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;
using Json = nlohmann::json;

constexpr double kRateHz = 2.0, kDurationS = 4200.0, kLagS = 300.0;

// The chamber's set point (°C) along the sweep, and the sensor 2 min behind it.
double set_point(double t) {
  if (t < 1500.0) return 52.0 - 70.0 * t / 1500.0;
  if (t < 3300.0) return -18.0 + 92.0 * (t - 1500.0) / 1800.0;
  return 74.0 - 34.0 * (t - 3300.0) / 900.0;
}

struct Sweep {
  std::vector<double> time_s, temp_c, bias_dps;  // bias: what the die's temperature makes it
};

// The die lags the sensor by lag_s (0: it is at the sensor's temperature).
Sweep sweep(double lag_s = kLagS) {
  Sweep s;
  double sensor = set_point(0.0), die = sensor;
  const double h = 1.0 / kRateHz;
  for (double t = 0.0; t <= kDurationS; t += h) {
    sensor += (set_point(t) - sensor) * (1.0 - std::exp(-h / 120.0));
    die = lag_s > 0.0 ? die + (sensor - die) * (1.0 - std::exp(-h / lag_s)) : sensor;
    s.time_s.push_back(t);
    s.temp_c.push_back(sensor);
    s.bias_dps.push_back(0.05 + 4e-3 * (die - 25.0) + 3e-5 * (die - 25.0) * (die - 25.0));
  }
  return s;
}

// The log, the x gyro with white noise of `sigma_dps` per sample.
void write_log(const std::filesystem::path& path, const Sweep& s, double sigma_dps) {
  boost::random::mt19937_64 rng(37);
  boost::random::normal_distribution<double> normal;
  std::ofstream out(path);
  out << "time_us\timu.temp\timu.gyro.x\timu.gyro.y\timu.gyro.z\timu.acc.x\timu.acc.y\timu.acc.z\timu.status\n";
  for (std::size_t k = 0; k < s.time_s.size(); ++k) {
    const double dt = s.temp_c[k] - 25.0;
    out << fmt::format("{}\t{:.3f}\t{:.6f}\t{:.6f}\t{:.6f}\t{:.4f}\t{:.4f}\t{:.4f}\t3\n",
                       static_cast<long long>(1.0e6 * s.time_s[k]) + 71265000000LL, s.temp_c[k],
                       s.bias_dps[k] + sigma_dps * normal(rng), -0.02 + 2e-3 * dt + 0.01 * normal(rng),
                       0.01 - 1e-3 * dt + 0.01 * normal(rng), 0.01 * normal(rng) + 1e-4 * dt,
                       0.01 * normal(rng), 9.81 + 0.01 * normal(rng));
  }
}

constexpr const char* kColumns =
    " --time-col time_us --time-unit us --temp-col imu.temp --gyro-col imu.gyro.x --gyro-unit dps --avg 60";

TEST(DiagnoseSweep, AHiddenLagAtTwentyTimesTheFloorIsNamedFirstAndSignificant) {
  ScratchDir dir;
  const Sweep s = sweep();
  // The paper's model's residual on the noise-free log sets the noise: its
  // window means' σ a twentieth of that residual.
  write_log(dir / "clean.tsv", s, 0.0);
  const auto clean = run_cli(dir, std::string("fit clean.tsv --json") + kColumns);
  ASSERT_EQ(clean.exit_code, 0) << clean.err;
  const double residual_dph = Json::parse(clean.out)["instability_after_dph"].get<double>();
  ASSERT_GT(residual_dph, 0.0);
  const double window_sigma_dps = residual_dph / 3600.0 / 20.0;
  write_log(dir / "sweep.tsv", s, window_sigma_dps * std::sqrt(60.0 * kRateHz));

  const auto r = run_cli(dir, std::string("diagnose sweep.tsv --json") + kColumns);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  const Json& channel = j.contains("channels") ? j["channels"][0] : j;
  EXPECT_GT(channel["ratio_to_floor"].get<double>(), 10.0) << channel["verdict"];
  const Json& first = channel["missing_effects"][0];
  const auto with = first["confounded_with"].get<std::vector<std::string>>();
  EXPECT_TRUE(first["term"] == "lag" || std::find(with.begin(), with.end(), "lag") != with.end())
      << first["term"] << ": " << channel["verdict"];
  EXPECT_TRUE(first["significant"].get<bool>() || first["group_significant"].get<bool>()) << channel["verdict"];
  // The log's other channels are sensors, not causes: no candidate.
  for (const Json& m : channel["missing_effects"]) {
    const std::string term = m["term"];
    EXPECT_EQ(term.find("imu."), std::string::npos) << term;
  }
  // The next step repeats the columns and units given: it runs as printed.
  const std::string next = channel["next_command"];
  ASSERT_EQ(next.rfind("gyrotherm diagnose sweep.tsv --model ", 0), 0u) << next;
  for (const char* given : {"--time-col time_us", "--time-unit us", "--gyro-col imu.gyro.x", "--avg 60"})
    EXPECT_NE(next.find(given), std::string::npos) << next;
  const auto again = run_cli(dir, next.substr(std::string("gyrotherm ").size()));
  EXPECT_EQ(again.exit_code, 0) << again.err;
  // Times since the record's start, not the logger's clock (71265 s in).
  for (const Json& seg : channel["segments"]) EXPECT_LT(seg["end_s"].get<double>(), kDurationS + 60.0);
}

// A MEMS gyro's large temperature slope makes dT sensitive to the sensor's
// own lag: fit says so, --sensor-tau is checked, and a de-lagged fit is not
// exported (no firmware de-lags).
TEST(DiagnoseSweep, ALagTheRecordCannotExcludeIsACautionAndADelaggedFitIsNotExported) {
  ScratchDir dir;
  write_log(dir / "sweep.tsv", sweep(0.0), 0.002);  // the paper's model holds: intervals from the noise alone
  const auto fit = run_cli(dir, std::string("fit sweep.tsv") + kColumns);
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NE(fit.out.find("caution, dT: a temperature sensor lagging the gyro by"), std::string::npos) << fit.out;
  EXPECT_NE(fit.out.find("give the sensor's time constant with --sensor-tau"), std::string::npos) << fit.out;
  const auto json = run_cli(dir, std::string("fit sweep.tsv --json") + kColumns);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_LT(Json::parse(json.out)["lag_to_move_by_interval_s"]["dT"].get<double>(), 60.0);

  for (const char* bad : {"-5", "nan"}) {
    const auto r = run_cli(dir, std::string("fit sweep.tsv --sensor-tau ") + bad + kColumns);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.err.find(std::string("--sensor-tau '") + bad + "': must be >= 0 s"),
              std::string::npos)
        << r.err;
  }
  const auto delagged = run_cli(dir, std::string("fit sweep.tsv --sensor-tau 20 -o fit.json") + kColumns);
  ASSERT_EQ(delagged.exit_code, 0) << delagged.err;
  const auto exported = run_cli(dir, "export fit.json --format c -o comp.h");
  EXPECT_EQ(exported.exit_code, 2);
  EXPECT_NE(exported.err.find("de-lagged by --sensor-tau 20 s, which no exported form applies"), std::string::npos)
      << exported.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "comp.h"));
}

}  // namespace
}  // namespace gyrotherm
