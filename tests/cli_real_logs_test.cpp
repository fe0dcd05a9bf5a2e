// Real measurement logs (issue 12): bursts, short records, units, several gyro
// channels; the PAN cubesat's thermal-vacuum log when the shared real-data folder beside the
// repository holds it.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.h"
#include "sim/config_loader.h"
#include "sim/simulator.h"

namespace gyrotherm {
namespace {

using namespace gyrotherm::testing;
namespace fs = std::filesystem;
using Json = nlohmann::json;

// The PAN log lives outside the repository (its licence note stays with it).
fs::path pan_folder() { return fs::path(GYROTHERM_SOURCE_DIR) / ".." / "shared" / "data" / "real" / "pan_tvac"; }

#define SKIP_WITHOUT_PAN()                                                            \
  if (!fs::exists(pan_folder() / "pan_tvac_3axis.csv"))                               \
  GTEST_SKIP() << "the PAN log is not at " << pan_folder().string()                   \
               << " (../shared/data/real/pan_tvac/): skipped"

// A path for the shell.
std::string quoted(const fs::path& p) { return fmt::format("'{}'", p.string()); }

const std::string kRawOptions =
    "--time-col 'time (ms)' --time-unit ms "
    "--gyro-col 'gyrox rad/s,gyroy rad/s,gyroz rad/s' --gyro-unit rad/s --gyro-scale 0.5 "
    "--temp-col temp --temp-scale 0.00390625 --temp-offset -231";

TEST(RealLogs, PanLogFitsAllThreeAxesWithDefaultOptions) {
  SKIP_WITHOUT_PAN();
  ScratchDir dir;
  const std::string csv = quoted(pan_folder() / "pan_tvac_3axis.csv");
  const auto r = run_cli(dir, "fit " + csv + " --gyro-col gx_dph,gy_dph,gz_dph --model T --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 3u);
  // The README's per-axis sensitivities from a straight line through the burst means.
  const double expected[3] = {107.0, -51.0, 5.0}, tolerance[3] = {5.0, 3.0, 1.5};
  for (int a = 0; a < 3; ++a) {
    const Json& c = j["channels"][a];
    EXPECT_EQ(c["channel"], fmt::format("g{}_dph", "xyz"[a]));
    EXPECT_NEAR(c["coefficients"]["T"].get<double>(), expected[a], tolerance[a]) << c["channel"];
    EXPECT_EQ(c["data"]["windows"].get<int>(), 25);
    EXPECT_TRUE(c["data"]["bursts"].get<bool>());
  }
  // With every option at its default (the paper's model) too.
  const auto defaults = run_cli(dir, "fit " + csv + " --gyro-col gx_dph,gy_dph,gz_dph");
  EXPECT_EQ(defaults.exit_code, 0) << defaults.err;
  // The human report says what happened to the bursts, per channel and in a summary.
  const auto human = run_cli(dir, "fit " + csv + " --gyro-col gx_dph,gy_dph,gz_dph --model T");
  ASSERT_EQ(human.exit_code, 0) << human.err;
  for (const char* fragment : {"25 bursts of 5 s every 30", "== channel gy_dph ==", "summary (3 channels",
                               "std of the burst means"})
    EXPECT_NE(human.out.find(fragment), std::string::npos) << fragment << " not in:\n" << human.out;
}

TEST(RealLogs, PanRawFileWithUnitOptionsGivesTheConvertedFilesResults) {
  SKIP_WITHOUT_PAN();
  ScratchDir dir;
  const std::string raw = quoted(pan_folder() / "TVCtest3_7_20.csv");
  const std::string converted = quoted(pan_folder() / "pan_tvac_3axis.csv");
  const auto a = run_cli(dir, "fit " + raw + " " + kRawOptions + " --model T --json");
  const auto b = run_cli(dir, "fit " + converted + " --gyro-col gx_dph,gy_dph,gz_dph --model T --json");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const Json ja = Json::parse(a.out), jb = Json::parse(b.out);
  for (int c = 0; c < 3; ++c) {
    // The converted file holds 6 significant digits of the same numbers.
    for (const char* term : {"1", "T"})
      EXPECT_NEAR(ja["channels"][c]["coefficients"][term].get<double>() /
                      jb["channels"][c]["coefficients"][term].get<double>(),
                  1.0, 1e-4)
          << c << " " << term;
    EXPECT_NE(ja["channels"][c]["pipeline"]["columns"]["units"]["conversion"].get<std::string>().find(
                  "rad/s → °/h"),
              std::string::npos);
  }
  // diagnose too, from the raw file.
  const auto d = run_cli(dir, "diagnose " + raw + " " + kRawOptions + " --json");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_EQ(Json::parse(d.out)["channels"].size(), 3u);
}

TEST(RealLogs, PanDiagnosisSaysWhatTheRecordCannotTell) {
  SKIP_WITHOUT_PAN();
  ScratchDir dir;
  const std::string csv = quoted(pan_folder() / "pan_tvac_3axis.csv");
  const auto r = run_cli(dir, "diagnose " + csv + " --gyro-col gx_dph,gy_dph,gz_dph --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 3u);
  for (const Json& c : j["channels"]) {
    SCOPED_TRACE(c["channel"].get<std::string>());
    EXPECT_GT(c["noise_floor_dph"].get<double>(), 0.0);
    EXPECT_FALSE(c["noise_floor"]["method"].get<std::string>().empty());
    // Temperature and time cannot be told apart on a cooling-only record.
    EXPECT_TRUE(testing::in_one_group(c["confounded"], "t", "T")) << c["confounding"];
    std::string notes;
    for (const Json& n : c["confounding"]) notes += n.get<std::string>();
    EXPECT_NE(notes.find("only cools"), std::string::npos) << notes;
    // No candidate confounded with others is called significant alone.
    for (const Json& m : c["missing_effects"])
      if (m["significant"].get<bool>()) {
        EXPECT_TRUE(m["confounded_with"].empty()) << m;
      }
  }
  const auto human = run_cli(dir, "diagnose " + csv + " --gyro-col gx_dph");
  ASSERT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("cannot be told apart"), std::string::npos) << human.out;
}

// A bursty logger on a heating-and-cooling profile: 60 s bursts every 300 s
// of the simulated cycle with a hidden gradient; the effect is recovered and
// diagnosed as on the continuous record.
TEST(RealLogs, SimulatedBurstsFindAHiddenEffectAsAContinuousRecordDoes) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "--hidden grad=0.0533", "full.csv");
  std::ifstream in(dir / "full.csv");
  std::ofstream out(dir / "bursts.csv");
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line.rfind("time_s", 0) == 0) {
      out << line << "\n";
      continue;
    }
    if (std::fmod(std::stod(line.substr(0, line.find(','))), 300.0) < 60.0) out << line << "\n";
  }
  out.close();
  const auto d = run_cli(dir, "diagnose bursts.csv --json");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const Json j = Json::parse(d.out);
  EXPECT_EQ(j["missing_effects"][0]["term"], "grad") << j["verdict"];
  EXPECT_TRUE(j["missing_effects"][0]["significant"].get<bool>());
  const auto f = run_cli(dir, "fit bursts.csv --add grad --json");
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const Json fj = Json::parse(f.out);
  EXPECT_TRUE(fj["data"]["bursts"].get<bool>());
  const auto interval = fj["intervals_95"]["grad"];
  EXPECT_LE(interval[0].get<double>(), 0.0533);
  EXPECT_GE(interval[1].get<double>(), 0.0533);
}

// Three axes in rad/s, each with its own temperature coefficient: each is
// recovered, and the several-channel run equals three single-channel runs.
TEST(RealLogs, ThreeAxesInRadiansPerSecondAreEachRecovered) {
  ScratchDir dir;
  sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  const sim::RigConfig rig = sim::load_rig(sc.rig_file);
  const double b1[3] = {2e-3, -1e-3, 5e-4};
  std::vector<sim::SimulationResult> axes;
  for (int a = 0; a < 3; ++a) {
    sim::GyroConfig g = sim::load_gyro(sc.gyro_file);
    g.coefficient["T"] = b1[a];
    g.noise.glitch_rate_per_h = 0.0;
    sc.seed = 100 + static_cast<std::uint64_t>(a);
    axes.push_back(sim::Simulator(sc, rig, g).run());
  }
  constexpr double kDphPerRadS = 3600.0 * 57.29577951308232;
  std::ofstream out(dir / "imu.csv");
  out << "time_s,temp_c,gx,gy,gz\n";
  for (std::size_t k = 0; k < axes[0].rows(); ++k)
    out << fmt::format("{:.10g},{:.5f},{:.12g},{:.12g},{:.12g}\n", axes[0].time_s[k], axes[0].temp_c[k],
                       axes[0].gyro_dph[k] / kDphPerRadS, axes[1].gyro_dph[k] / kDphPerRadS,
                       axes[2].gyro_dph[k] / kDphPerRadS);
  out.close();
  const auto all = run_cli(dir, "fit imu.csv --gyro-col gx,gy,gz --gyro-unit rad/s --json -o fit.json");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const Json j = Json::parse(all.out);
  ASSERT_EQ(j["channels"].size(), 3u);
  for (int a = 0; a < 3; ++a) {
    const std::string name = fmt::format("g{}", "xyz"[a]);
    const Json& c = j["channels"][a];
    EXPECT_EQ(c["channel"], name);
    EXPECT_NEAR(c["coefficients"]["T"].get<double>() / b1[a], 1.0, 0.1) << name;
    const auto one = run_cli(dir, "fit imu.csv --gyro-col " + name + " --gyro-unit rad/s --json");
    ASSERT_EQ(one.exit_code, 0) << one.err;
    EXPECT_EQ(Json::parse(one.out)["coefficients"], c["coefficients"]) << name;
  }
  // compensate applies each channel of the saved fit.
  const auto comp = run_cli(dir, "compensate imu.csv --fit fit.json -o comp.csv --json");
  ASSERT_EQ(comp.exit_code, 0) << comp.err;
  EXPECT_EQ(Json::parse(comp.out)["channels"].size(), 3u);
  const std::string header = slurp(dir / "comp.csv");
  for (const char* column : {"gx_compensated_dph", "gy_model_dph", "gz_outlier"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
}

// PX4's offboard recipe: a 45-minute warm-up logged at 100 Hz.
TEST(RealLogs, AShortFastWarmUpFitsAndDiagnosesWithShortWindows) {
  ScratchDir dir;
  write_text(dir / "warm.toml",
             "name = \"warm45\"\nrig = \"" + source_path("scenarios/rig_room.toml") + "\"\ngyro = \"" +
                 source_path("scenarios/gyro.toml") +
                 "\"\nseed = 7\nsample_rate_hz = 100.0\nroom_c = 23.0\nchamber = false\ninitial = \"soaked\"\n"
                 "[[segment]]\nkind = \"free\"\nduration_min = 45\n");
  ASSERT_EQ(run_cli(dir, "simulate warm.toml -o warm.csv").exit_code, 0);
  for (const char* window : {"10", "30"}) {
    SCOPED_TRACE(window);
    const auto f = run_cli(dir, std::string("fit warm.csv --avg ") + window + " --json");
    ASSERT_EQ(f.exit_code, 0) << f.err;
    const auto d = run_cli(dir, std::string("diagnose warm.csv --avg ") + window + " --json");
    ASSERT_EQ(d.exit_code, 0) << d.err;
    const Json j = Json::parse(d.out);
    EXPECT_GT(j["noise_floor_dph"].get<double>(), 0.0);
    EXPECT_FALSE(j["verdict"].get<std::string>().empty());
  }
}

// From 8 windows up: the floor from inside the windows when there are too
// few for the Hadamard estimate, fewer candidates when the record cannot
// support more, both said; fewer than 8 windows are refused.
TEST(RealLogs, DiagnoseWorksFromEightWindowsAndSaysWhatItCouldNotTry) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  const auto r = run_cli(dir, "diagnose c.csv --avg 3600 --model 'T + T^2 + dT + grad' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["noise_floor"]["method"], "within-window scatter");
  EXPECT_LT(j["noise_floor"]["hadamard_triples"].get<int>(), 10);
  int not_tried = 0;
  for (const Json& s : j["skipped"]) not_tried += s.get<std::string>().find("not tried") != std::string::npos;
  EXPECT_GE(not_tried, 1) << j["skipped"];
  EXPECT_NE(j["verdict"].get<std::string>().find("fewer tests"), std::string::npos) << j["verdict"];
  const auto fit = run_cli(dir, "fit c.csv --avg 3600");
  EXPECT_EQ(fit.exit_code, 0) << fit.err;
  const auto few = run_cli(dir, "diagnose c.csv --avg 5000");
  EXPECT_EQ(few.exit_code, 2);
  EXPECT_NE(few.err.find("only 6 windows: diagnose needs at least 8"), std::string::npos) << few.err;
}

struct BadLog {
  std::string name;
  std::string args;  // after the command
  std::vector<std::string> fragments;
};
void PrintTo(const BadLog& b, std::ostream* os) { *os << b.name; }

class RealLogBadInput : public ::testing::TestWithParam<BadLog> {};

TEST_P(RealLogBadInput, NamesTheProblemExitsTwoWritesNothing) {
  ScratchDir dir;
  std::ofstream out(dir / "imu.csv");
  out << "time_s,temp_c,gx,gy,gflat\n";
  for (int k = 0; k < 2000; ++k)
    out << k << "," << 20.0 + 10.0 * std::sin(k / 300.0) << "," << 5.0 + 0.01 * k + (k % 7) * 0.1 << ","
        << -3.0 + (k % 5) * 0.2 << ",7\n";
  out.close();
  for (const char* command : {"fit", "diagnose"}) {
    const auto r = run_cli(dir, std::string(command) + " imu.csv " + GetParam().args + " -o out.json");
    if (std::string(command) == "diagnose") continue;  // diagnose has no -o; checked below
    EXPECT_EQ(r.exit_code, 2) << r.out;
    for (const std::string& f : GetParam().fragments) EXPECT_NE(r.err.find(f), std::string::npos) << f << " in " << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.json"));
  }
  const auto d = run_cli(dir, "diagnose imu.csv " + GetParam().args);
  EXPECT_EQ(d.exit_code, 2) << d.out;
  for (const std::string& f : GetParam().fragments) EXPECT_NE(d.err.find(f), std::string::npos) << f << " in " << d.err;
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, RealLogBadInput,
    ::testing::Values(
        BadLog{"unknown_gyro_unit", "--gyro-col gx --gyro-unit deg/hr", {"--gyro-unit deg/hr: unknown unit", "dph, dps, rad/s"}},
        BadLog{"unknown_time_unit", "--gyro-col gx --time-unit fortnight", {"--time-unit fortnight: unknown unit"}},
        BadLog{"zero_scale", "--gyro-col gx --gyro-scale 0", {"--gyro-scale 0", "other than 0"}},
        BadLog{"missing_channel", "--gyro-col gx,gz", {"channel gz", "no column 'gz'"}},
        BadLog{"constant_channel", "--gyro-col gflat", {"the gyro output is constant"}},
        BadLog{"good_and_bad_channels", "--gyro-col gx,gflat", {"channel gflat", "constant"}},
        BadLog{"channel_named_twice", "--gyro-col gx,gx", {"'gx' is named twice"}}),
    [](const auto& param_info) { return param_info.param.name; });


// allan on the PAN log: three axes in bursts of 5 s every 30 s. It reports
// what the bursts allow (τ up to half a burst), says that the runs limit it, counts the clusters a gap would cut,
// and shows the ARW region but not the bias instability.
TEST(RealLogs, PanAllanReportsWhatTheBurstsAllow) {
  SKIP_WITHOUT_PAN();
  ScratchDir dir;
  const std::string csv = quoted(pan_folder() / "pan_tvac_3axis.csv");
  const auto r = run_cli(dir, "allan " + csv + " --gyro-col gx_dph,gy_dph,gz_dph --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 3u);
  for (const Json& c : j["channels"]) {
    const Json& s = c["series"][0];
    EXPECT_EQ(s["runs"].get<int>(), 25);
    EXPECT_TRUE(s["limited_by_runs"].get<bool>());
    EXPECT_LE(s["taus_s"].back().get<double>(), s["longest_run_s"].get<double>() / 2.0);
    EXPECT_GT(s["gap_terms"].back().get<int>(), 0);
    EXPECT_TRUE(s["coefficients"]["arw_dpsh"]["shown"].get<bool>()) << c["channel"];
    EXPECT_FALSE(s["coefficients"]["bias_instability_dph"]["shown"].get<bool>()) << c["channel"];
  }
  const auto human = run_cli(dir, "allan " + csv + " --gyro-col gx_dph,gy_dph,gz_dph");
  ASSERT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("the runs are short"), std::string::npos) << human.out;
}

}  // namespace
}  // namespace gyrotherm
