// The whole IMU's round trip with a known truth: `simulate` writes the
// shipped MEMS IMU (scenarios/imu.toml: a three-axis gyro, a three-axis
// accelerometer and a barometer) as a PX4 ULog and an ArduPilot DataFlash
// log; `fit --sensor` fits each sensor; `export` writes PX4's TC_G/TC_A/TC_B
// and ArduPilot's INS_TCAL1_GYR/ACC; each file applied by its firmware's
// rule (tests/parameter_files.h, written from the firmware sources) leaves
// the instability export predicted, to 1e-9; and over 50 seeds the
// coefficients' 95 % intervals hold the simulator's truth at least 90 % of
// the time, for each sensor.

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "fit/data/measurement.h"
#include "parameter_files.h"

namespace gyrotherm::studies {
namespace {

using testing::CliResult, testing::run_cli, testing::ScratchDir, testing::slurp, testing::source_path;

constexpr const char* kCubic = "--model 'T + T^2 + T^3'";

nlohmann::json imu_fit_json(const ScratchDir& dir, const std::string& args) {
  const CliResult r = run_cli(dir, "fit " + args + " --json");
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

// A fit's channels: several under "channels", one as the fit itself.
std::vector<nlohmann::json> channels_of(const nlohmann::json& j) {
  std::vector<nlohmann::json> out;
  if (!j.contains("channels")) return {j};
  for (const auto& c : j["channels"]) out.push_back(c);
  return out;
}

struct Sensor {
  const char* name;      // --sensor
  const char* stem;      // PX4's parameter stem
  int px4_order;         // its polynomial's order
  const char* group;     // ArduPilot's INS_TCAL group, "" for none
  double per_base;       // the log's unit per the fit's
  std::vector<std::string> columns;  // as the log reader names them
};
const std::vector<Sensor>& sensors() {
  static const std::vector<Sensor> list = {
      {"gyro", "TC_G0", 3, "GYR", testing::kDphToRadS, {"gyro_x", "gyro_y", "gyro_z"}},
      {"accel", "TC_A0", 3, "ACC", 1.0, {"accel_x", "accel_y", "accel_z"}},
      {"baro", "TC_B0", 5, "", 1.0, {"pressure"}},
  };
  return list;
}

// Axis a of `sensor` in `log`, as export's outcome reads it.
fit::Measurement axis_record(const ScratchDir& dir, const std::string& log, const Sensor& sensor, std::size_t a) {
  fit::ColumnMap map;
  map.gyro = sensor.columns[a];
  if (std::string(sensor.name) != "gyro") map.units.sensor = sensor.name;
  return fit::read_measurement_csv(dir / log, map);
}

TEST(ImuRoundTrip, EachFirmwaresFileLeavesWhatExportPredictedOnBothLogs) {
  ScratchDir dir;
  for (const char* log : {"imu.ulg", "imu.bin"}) {
    const CliResult made = run_cli(dir, fmt::format("simulate {} -o {}", source_path("scenarios/imu.toml"), log));
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const bool ulog = std::string(log) == "imu.ulg";
    for (const Sensor& sensor : sensors()) {
      const std::string fit_file = fmt::format("{}_{}.json", sensor.name, ulog ? "px4" : "ap");
      const nlohmann::json fitted = imu_fit_json(dir, fmt::format("{} --sensor {} {} -o {}", log, sensor.name, kCubic, fit_file));
      const std::vector<nlohmann::json> channels = channels_of(fitted);
      ASSERT_EQ(channels.size(), sensor.columns.size()) << log << " " << sensor.name;
      for (const nlohmann::json& c : channels) EXPECT_TRUE(c.contains("truth")) << "each channel meets its truth";
      // PX4 from the ULog (and the barometer from both: ArduPilot has none).
      const bool px4 = ulog || std::string(sensor.group).empty();
      const std::string out = fmt::format("{}_{}.par", sensor.name, ulog ? "px4" : "ap");
      const CliResult exported =
          run_cli(dir, fmt::format("export {} --format {} --accept-caution --json -o {}{}", fit_file,
                                   px4 ? "px4" : "ardupilot", out, px4 ? "" : " --boot-temp 25"));
      ASSERT_EQ(exported.exit_code, 0) << exported.err;
      const nlohmann::json outcome = nlohmann::json::parse(exported.out)["firmware_outcome"];
      const std::string text = slurp(dir / out);
      for (std::size_t a = 0; a < sensor.columns.size(); ++a) {
        const fit::Measurement m = axis_record(dir, log, sensor, a);
        std::vector<double> applied;
        if (px4) {
          const auto p = testing::read_qgc(text);
          const std::string suffix = sensor.columns.size() == 1 ? "" : "_" + std::to_string(a);
          applied = testing::px4_as_applied(
              m, [&](float t) { return testing::px4_offset_of(p, sensor.stem, suffix, sensor.px4_order, t); },
              sensor.per_base);
        } else {
          const auto p = testing::read_ap(text);
          for (const double t : m.temp_c)
            applied.push_back(testing::ardupilot_subtracted(p, "XYZ"[a], static_cast<float>(t), 25.0f, sensor.group) /
                              sensor.per_base);
        }
        const double expected = testing::instability(m, applied);
        const double predicted = outcome["axes"][a]["firmware_dph"].get<double>();
        EXPECT_NEAR(predicted, expected, 1e-9 * expected) << log << " " << sensor.name << " " << a;
        // And the firmware takes out nearly all of the thermal drift.
        EXPECT_LT(predicted, 0.1 * outcome["axes"][a]["instability_before_dph"].get<double>())
            << log << " " << sensor.name << " " << a;
      }
    }
  }
}

// For each sensor, how many of its coefficients' intervals (every axis and
// every term; the constant has none) held the truth, and of how many.
struct Tally {
  int held = 0, total = 0;
  std::map<std::string, int> missed;  // "gyro_z T^3" → seeds it missed
};

void tally(const nlohmann::json& channel, const std::string& sensor, Tally& t) {
  const nlohmann::json& truth = channel["truth"];
  const nlohmann::json& intervals = channel["intervals_95"];
  for (const auto& [term, value] : channel["coefficients"].items()) {
    if (!intervals.contains(term)) continue;
    const double lo = intervals[term][0], hi = intervals[term][1];
    const double true_value = truth.contains(term) ? truth[term].get<double>() : 0.0;
    const bool held = lo <= true_value && true_value <= hi;
    t.held += held;
    ++t.total;
    if (!held) ++t.missed[sensor + " " + channel["pipeline"]["columns"]["gyro"].get<std::string>() + " " + term];
  }
}

TEST(ImuRoundTrip, CoefficientIntervalsCoverTheTruthOverFiftySeeds) {
  ScratchDir dir;
  std::map<std::string, Tally> tallies;
  for (int seed = 1; seed <= 50; ++seed) {
    const CliResult made =
        run_cli(dir, fmt::format("simulate {} --seed {} -o s.ulg", source_path("scenarios/imu.toml"), seed));
    ASSERT_EQ(made.exit_code, 0) << made.err;
    for (const Sensor& sensor : sensors())
      for (const nlohmann::json& c : channels_of(imu_fit_json(dir, fmt::format("s.ulg --sensor {} {}", sensor.name, kCubic)))) {
        ASSERT_TRUE(c.contains("truth") && c.contains("intervals_95")) << c.dump().substr(0, 400);
        tally(c, sensor.name, tallies[sensor.name]);
      }
  }
  for (const auto& [sensor, t] : tallies) {
    std::string missed;
    for (const auto& [what, n] : t.missed) missed += fmt::format("{}: {}; ", what, n);
    const double coverage = static_cast<double>(t.held) / t.total;
    EXPECT_GE(coverage, 0.90) << sensor << " " << t.held << " of " << t.total << "; missed " << missed;
    // No one coefficient far below (a bias the pooled figure would hide):
    // at 95 % a coefficient misses more than 10 of 50 with probability 1e-4.
    for (const auto& [what, n] : t.missed) EXPECT_LE(n, 10) << what;
    RecordProperty(sensor + "_coverage", fmt::format("{:.3f}", coverage));
  }
}

}  // namespace
}  // namespace gyrotherm::studies
