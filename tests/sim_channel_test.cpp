// The simulator's channels beside the gyro (sim/channel.h) and the
// autopilot logs it writes (sim/record_format.h): each channel is its
// polynomial in the true temperature plus white noise of its density, the
// gyro's own column and the temperatures are as they were without channels,
// a ULog or DataFlash log holds every sample as the format stores it (read
// back by the project's readers), the truth beside the log names each
// channel's coefficients, and a gyro file that cannot make the log asked for
// is refused before anything is simulated or written.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "fit/data/autopilot_log.h"
#include "fit/data/sensor_kind.h"
#include "sim/config_loader.h"
#include "sim/record_format.h"
#include "sim/simulator.h"

namespace gyrotherm::sim {
namespace {

using testing::CliResult, testing::expect_refused, testing::run_cli, testing::ScratchDir, testing::source_path;

struct Imu {
  Scenario scenario;
  RigConfig rig;
  GyroConfig gyro;
};
Imu shipped_imu() {
  Imu imu{load_scenario(source_path("scenarios/imu.toml")), {}, {}};
  imu.rig = load_rig(imu.scenario.rig_file);
  imu.gyro = load_gyro(imu.scenario.gyro_file);
  return imu;
}

// b0 + c_T·T + c_T²·T² + c_T³·T³: the shipped channels' terms.
double polynomial(const ChannelConfig& ch, double t) {
  auto c = [&](const char* term) { return ch.coefficient.count(term) ? ch.coefficient.at(term) : 0.0; };
  EXPECT_EQ(ch.coefficient.size(), static_cast<std::size_t>((c("T") != 0) + (c("T^2") != 0) + (c("T^3") != 0)));
  return ch.b0 + t * (c("T") + t * (c("T^2") + t * c("T^3")));
}

TEST(SimChannel, EachChannelIsItsPolynomialInTheTrueTemperatureWithItsWhiteNoise) {
  const Imu imu = shipped_imu();
  ASSERT_EQ(imu.gyro.channels.size(), 6u);
  const Simulator simulator(imu.scenario, imu.rig, imu.gyro);
  const SimulationResult r = simulator.run();
  const std::vector<double>& t = r.truth.node(RigDynamics::anode);
  ASSERT_EQ(r.channels.size(), 6u);
  for (std::size_t i = 0; i < r.channels.size(); ++i) {
    const ChannelConfig& ch = imu.gyro.channels[i];
    const SimulationResult::Channel& c = r.channels[i];
    ASSERT_EQ(c.value.size(), r.rows());
    double worst = 0.0, sum = 0.0, sum2 = 0.0;
    for (std::size_t k = 0; k < r.rows(); ++k) {
      worst = std::max(worst, std::abs(c.truth[k] - polynomial(ch, t[k])));
      const double e = c.value[k] - c.truth[k];
      sum += e;
      sum2 += e * e;
    }
    const double n = static_cast<double>(r.rows());
    const double sigma = ch.white_noise * std::sqrt(imu.scenario.sample_rate_hz);
    EXPECT_LT(worst, 1e-12 * std::abs(ch.b0) + 1e-12) << ch.label();
    EXPECT_NEAR(std::sqrt(sum2 / n), sigma, 0.03 * sigma) << ch.label();  // its SE is 0.6 %
    EXPECT_NEAR(sum / n, 0.0, 4.0 * sigma / std::sqrt(n)) << ch.label();
  }
  // Every channel draws its own noise: no two are correlated.
  const auto noise = [&](std::size_t i, std::size_t k) { return r.channels[i].value[k] - r.channels[i].truth[k]; };
  double dot = 0.0, a2 = 0.0, b2 = 0.0;
  for (std::size_t k = 0; k < r.rows(); ++k) {
    dot += noise(3, k) * noise(4, k);
    a2 += noise(3, k) * noise(3, k);
    b2 += noise(4, k) * noise(4, k);
  }
  EXPECT_LT(std::abs(dot / std::sqrt(a2 * b2)), 4.0 / std::sqrt(static_cast<double>(r.rows())));
}

TEST(SimChannel, ChannelsLeaveTheGyroAndTheTemperaturesAsTheyWere) {
  Imu imu = shipped_imu();
  const SimulationResult with = Simulator(imu.scenario, imu.rig, imu.gyro).run();
  imu.gyro.channels.clear();
  const SimulationResult without = Simulator(imu.scenario, imu.rig, imu.gyro).run();
  EXPECT_EQ(with.gyro_dph, without.gyro_dph);
  EXPECT_EQ(with.temp_c, without.temp_c);
  EXPECT_EQ(with.chamber_c, without.chamber_c);
  EXPECT_TRUE(without.channels.empty());
}

// Every sample of `kind` in `log` (instance 0) as the reader gives it.
struct Read {
  std::vector<double> temp, x, y, z;
};
Read read_log(fit::AutopilotReader read, const std::filesystem::path& log, const char* kind) {
  Read out;
  read(log, 0, [&](double, double tc, double x, double y, double z) {
    out.temp.push_back(tc);
    out.x.push_back(x);
    out.y.push_back(y);
    out.z.push_back(z);
  }, fit::sensor_kind(kind));
  return out;
}

TEST(SimChannel, AnAutopilotLogHoldsEverySampleAsItsFormatStoresIt) {
  ScratchDir dir;
  const Imu imu = shipped_imu();
  const SimulationResult r = Simulator(imu.scenario, imu.rig, imu.gyro).run();
  for (const char* log : {"imu.ulg", "imu.bin", "imu.csv"}) {
    const CliResult made = run_cli(dir, "simulate " + source_path("scenarios/imu.toml") + " -o " + log + " --json");
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const nlohmann::json j = nlohmann::json::parse(made.out);
    EXPECT_EQ(j["channels"].size(), 6u);
    EXPECT_EQ(j.value("format", "CSV"), std::string(log) == "imu.ulg" ? "PX4 ULog"
                                        : std::string(log) == "imu.bin" ? "ArduPilot DataFlash log"
                                                                        : "CSV");
  }
  const GyroConfig& g = imu.gyro;
  const auto as_float = [](double v, double scale) { return static_cast<double>(static_cast<float>(v * scale)); };
  for (const bool ulog : {true, false}) {
    const fit::AutopilotReader read = ulog ? &fit::read_ulog : &fit::read_dataflash;
    const std::filesystem::path file = dir / (ulog ? "imu.ulg" : "imu.bin");
    const Read gyro = read_log(read, file, "gyro"), accel = read_log(read, file, "accel"),
               baro = read_log(read, file, "baro");
    ASSERT_EQ(gyro.x.size(), r.rows());
    ASSERT_EQ(accel.x.size(), r.rows());
    ASSERT_EQ(baro.x.size(), r.rows());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < r.rows(); ++k) {
      differ += gyro.x[k] != as_float(r.gyro_dph[k], kRadPerSecondPerDph);
      differ += gyro.y[k] != as_float(channel_values(g, r, "gyro", 'y')[k], kRadPerSecondPerDph);
      differ += gyro.z[k] != as_float(channel_values(g, r, "gyro", 'z')[k], kRadPerSecondPerDph);
      differ += accel.x[k] != as_float(channel_values(g, r, "accel", 'x')[k], 1.0);
      differ += accel.z[k] != as_float(channel_values(g, r, "accel", 'z')[k], 1.0);
      differ += baro.x[k] != as_float(channel_values(g, r, "baro", 0)[k], 1.0);
      differ += gyro.temp[k] != as_float(r.temp_c[k], 1.0);
      // ArduPilot's BARO keeps centidegrees.
      differ += ulog ? baro.temp[k] != as_float(r.temp_c[k], 1.0)
                     : std::abs(baro.temp[k] - std::round(r.temp_c[k] * 100.0) / 100.0) > 1e-12;
    }
    EXPECT_EQ(differ, 0u) << file;
  }
  // The truth beside names each channel's coefficients and columns.
  const nlohmann::json truth = nlohmann::json::parse(testing::slurp(dir / "imu.truth.json"));
  ASSERT_EQ(truth["channels"].size(), 6u);
  EXPECT_EQ(truth["channels"][5]["sensor"], "baro");
  EXPECT_EQ(truth["channels"][5]["column"], "baro_pa");
  EXPECT_EQ(truth["channels"][5]["coefficients"]["T"], 4.0);
  EXPECT_EQ(truth["channels"][2]["truth_column"], "accel_x_true_mps2");
}

// imu.csv and imu.ulg share imu.truth.json: the truth names its record, and
// a fit of the other meets none rather than another seed's.
TEST(SimChannel, ATruthBelongsToTheRecordWrittenWithIt) {
  ScratchDir dir;
  const std::string imu = source_path("scenarios/imu.toml");
  ASSERT_EQ(run_cli(dir, "simulate " + imu + " --seed 1 -o imu.csv").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "simulate " + imu + " --seed 2 -o imu.ulg").exit_code, 0);
  const nlohmann::json truth = nlohmann::json::parse(testing::slurp(dir / "imu.truth.json"));
  EXPECT_EQ(truth["record"]["file"], "imu.ulg");
  EXPECT_EQ(truth["record"]["sha256"].get<std::string>().size(), 64u);
  const auto has_truth = [&](const std::string& args) {
    const CliResult r = run_cli(dir, "fit " + args + " --model T --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0 && nlohmann::json::parse(r.out).contains("truth");
  };
  EXPECT_TRUE(has_truth("imu.ulg --sensor baro"));
  EXPECT_FALSE(has_truth("imu.csv --sensor baro"));
}

TEST(SimChannel, AGyroFileThatCannotMakeTheLogAskedForIsRefused) {
  ScratchDir dir;
  const std::string gyro = "\n[truth]\nb0_dph = 1.0\n";
  auto refused = [&](const std::string& channels, const std::string& output, const std::string& message) {
    testing::write_text(dir / "g.toml", gyro + channels);
    expect_refused(dir, "simulate " + source_path("scenarios/imu.toml") + " --gyro g.toml -o " + output, message);
    EXPECT_FALSE(std::filesystem::exists(dir / output)) << output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.truth.json"));
  };
  refused("[[channel]]\nsensor = \"compass\"\n", "out.csv", "sensor = \"compass\": expected gyro, accel or baro");
  refused("[[channel]]\nsensor = \"accel\"\n", "out.csv", "sensor = \"accel\" needs axis = \"x\", \"y\" or \"z\"");
  refused("[[channel]]\nsensor = \"baro\"\naxis = \"x\"\n", "out.csv", "sensor = \"baro\" has no axes; drop axis");
  refused("[[channel]]\nsensor = \"gyro\"\naxis = \"x\"\n", "out.csv", "the gyro's axis x is the file's [truth]");
  refused("[[channel]]\nsensor = \"baro\"\n[[channel]]\nsensor = \"baro\"\n", "out.csv", "baro is simulated twice");
  refused("[[channel]]\nsensor = \"baro\"\nterms = { Q = 1.0 }\n", "out.csv", "unknown key 'channel 1.terms.Q'");
  refused("[[channel]]\nsensor = \"baro\"\nwhite_noise = -1.0\n", "out.csv", "must be >= 0");
  // A log needs every axis of the kinds it holds.
  refused("", "out.ulg", "a ULog's sensor_gyro holds the gyro's axes x, y and z, and the gyro file simulates no gyro y, gyro z");
  refused("[[channel]]\nsensor = \"gyro\"\naxis = \"y\"\n[[channel]]\nsensor = \"gyro\"\naxis = \"z\"\n"
          "[[channel]]\nsensor = \"accel\"\naxis = \"z\"\n",
          "out.ulg", "simulates no accel x, accel y");
  refused("[[channel]]\nsensor = \"gyro\"\naxis = \"y\"\n[[channel]]\nsensor = \"gyro\"\naxis = \"z\"\n", "out.bin",
          "a DataFlash IMU message holds the accel's axes x, y and z");
  // The extension in any case.
  ASSERT_EQ(run_cli(dir, "simulate " + source_path("scenarios/imu.toml") + " -o UPPER.ULG").exit_code, 0);
  EXPECT_EQ(fit::read_ulog(dir / "UPPER.ULG", -1, {}, fit::sensor_kind("accel")).default_instance(), 0);
  // A gyro with its other axes and no accelerometer is a ULog of gyros alone.
  testing::write_text(dir / "g.toml", gyro + "[[channel]]\nsensor = \"gyro\"\naxis = \"y\"\n[[channel]]\nsensor = "
                                             "\"gyro\"\naxis = \"z\"\n");
  ASSERT_EQ(run_cli(dir, "simulate " + source_path("scenarios/imu.toml") + " --gyro g.toml -o g.ulg").exit_code, 0);
  EXPECT_EQ(fit::read_ulog(dir / "g.ulg", -1, {}, fit::sensor_kind("accel")).default_instance(), -1);
}

}  // namespace
}  // namespace gyrotherm::sim
