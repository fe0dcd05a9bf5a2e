// What a firmware export achieves (studies/export/firmware_outcome.h): each
// firmware's rule for applying its parameters, written here again from the
// firmware's source (PX4 TemperatureCompensationModule, once a second, and
// TemperatureCompensation::update_offsets_gyro, re-published past 1 °C;
// ArduPilot TCal::correct_sensor, every sample, relative to the boot offsets),
// applied to the exported file as the firmware loads it: the instability
// export reports is that one. And only parameters the firmware has.

#include "studies/export/firmware_outcome.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.h"
#include "parameter_files.h"
#include "fit/data/prepare.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;


TEST(FirmwareOutcome, Px4HoldsTheOffsetsOfTheLastPublishedTemperature) {
  // 0.25 s samples, warming 0.3 °C/s, a gap from 3.5 to 7.25 s.
  std::vector<double> t, temp;
  for (double s = 0.0; s <= 12.0; s += 0.25) {
    if (s > 3.5 && s < 7.25) continue;
    t.push_back(s);
    temp.push_back(20.0 + 0.3 * s);
  }
  const std::array<float, 4> x = {1e-4f, 2e-5f, 1e-7f, 0.0f};
  const auto offset = [&](float at) {
    const float d = at - 20.0f;
    return static_cast<double>(x[0] + x[1] * d + x[2] * d * d + x[3] * d * d * d) / kDphToRadS;
  };
  const std::vector<double> applied = px4_applied_dph(t, temp, x, 20.0f, 0.0f, 100.0f);
  for (std::size_t i = 0; i < t.size(); ++i) {
    // Runs at 0, 1, 2, 3 s see 20, 20.3, 20.6, 20.9 °C: published at 0 only;
    // the first run after the gap (7.25 s, 22.175 °C) publishes; 8..10 s see
    // 22.4..23.0 °C, within 1 °C of it; 11 s sees 23.3 °C and publishes; 12 s
    // sees 23.6 °C, within 1 °C of that.
    const float published = t[i] < 7.25 ? 20.0f : t[i] < 11.0 ? static_cast<float>(20.0 + 0.3 * 7.25)
                                                               : static_cast<float>(20.0 + 0.3 * 11.0);
    EXPECT_EQ(applied[i], offset(published)) << "t = " << t[i];
  }
}

TEST(FirmwareOutcome, ArduPilotSubtractsTheBiasAtBootThere) {
  const std::array<float, 3> g = {50.0f, -2.0f, 0.01f};  // ×1e-6 rad/s per °C^k about 35 °C
  const std::vector<double> temp = {10.0, 30.0, 35.0, 60.0, 90.0};
  const std::vector<double> applied = ardupilot_applied_dph(temp, g, 15.0f, 70.0f, 30.0f, 7.5);
  EXPECT_DOUBLE_EQ(applied[1], 7.5);              // at the boot temperature: the boot offsets' bias
  EXPECT_EQ(applied[0], ardupilot_applied_dph({15.0}, g, 15.0f, 70.0f, 30.0f, 7.5)[0]);  // clamped below
  EXPECT_EQ(applied[4], ardupilot_applied_dph({70.0}, g, 15.0f, 70.0f, 30.0f, 7.5)[0]);  // and above
  // At 35 °C p is 0: what is subtracted is the bias at boot less p(30 − 35) (float: 1e-4 °/h).
  EXPECT_NEAR(applied[2] - 7.5, (0.0 - (-5.0 * (50.0 + (-2.0 + 0.01 * -5.0) * -5.0)) * 1e-6) / kDphToRadS, 1e-4);
}

// `export fit.json ARGS --json`'s firmware_outcome (null, and a failure, when it fails).
nlohmann::json outcome(const ScratchDir& dir, const std::string& args) {
  const auto r = run_cli(dir, "export fit.json " + args + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out)["firmware_outcome"] : nlohmann::json();
}

// A simulated cycle made three MEMS-like axes (20, −8, 0.5 °/h per °C and a
// curvature), fitted, exported for each firmware, and the exported file
// applied again here by each firmware's rule: export's numbers are these.
TEST(CliExport, WhatTheFirmwareAchievesIsItsRuleAppliedToTheExportedFile) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  write_columns(dir, "d.csv", "three.csv",
                {{"gx", "$6+20*$4+0.05*$4*$4"}, {"gy", "$6-8*$4"}, {"gz", "$6+0.5*$4"}});
  ASSERT_EQ(run_cli(dir, "fit three.csv --gyro-col gx,gy,gz --model 'T + T^2' -o fit.json").exit_code, 0);
  std::vector<fit::Measurement> axes;
  for (const char* gyro : {"gx", "gy", "gz"}) {
    fit::ColumnMap map;
    map.gyro = gyro;
    axes.push_back(fit::read_measurement_csv(dir / "three.csv", map));
  }
  const nlohmann::json fits = nlohmann::json::parse(slurp(dir / "fit.json"));

  const nlohmann::json px4 = outcome(dir, "--format px4 -o p.params");
  const auto p = read_qgc(slurp(dir / "p.params"));
  for (std::size_t a = 0; a < 3; ++a) {
    const double expected = instability(axes[a], px4_as_applied(axes[a], p, static_cast<int>(a)));
    EXPECT_NEAR(px4["axes"][a]["firmware_dph"].get<double>(), expected, 1e-9 * expected) << a;
    EXPECT_EQ(px4["axes"][a]["model_dph"], fits["channels"][a]["instability_after_dph"]);
  }
  // 20 °/h per °C held for up to 1 °C: PX4's steps cost gx far more than the
  // model (and than the exported cubic applied at every sample); said in a note.
  EXPECT_GT(px4["axes"][0]["firmware_dph"].get<double>(), 10.0 * px4["axes"][0]["exported_dph"].get<double>());
  ASSERT_FALSE(px4["notes"].empty());
  EXPECT_NE(px4["notes"][0].get<std::string>().find("X (gx): as PX4 applies it"), std::string::npos);

  const nlohmann::json ap = outcome(dir, "--format ardupilot --boot-temp 30 -o a.param");
  const auto q = read_ap(slurp(dir / "a.param"));
  for (std::size_t a = 0; a < 3; ++a) {
    std::vector<double> subtracted;
    for (const double temp : axes[a].temp_c)
      subtracted.push_back(ardupilot_subtracted(q, "XYZ"[a], static_cast<float>(temp), 30.0f) / kDphToRadS);
    const double expected = instability(axes[a], subtracted);
    EXPECT_NEAR(ap["axes"][a]["firmware_dph"].get<double>(), expected, 1e-9 * expected) << a;
  }
  // The same file without the data it was fitted on: written, and what it achieves is not claimed.
  run_shell(dir, "mv three.csv moved.csv");
  const auto blind = run_cli(dir, "export fit.json --format px4 -o blind.params");
  EXPECT_EQ(blind.exit_code, 0) << blind.err;
  EXPECT_NE(blind.out.find("is not predicted: the data fit.json was fitted on ('three.csv') is not here; give it with --data"),
            std::string::npos) << blind.out;
}

TEST(CliExport, OnlyParametersTheFirmwareHas) {
  ScratchDir dir;
  write_ramp_log(dir / "d.csv", "gyro_dph", {3.0}, 3.0, 10.0, 40.0, 7);
  ASSERT_EQ(run_cli(dir, "fit d.csv --model 'T + T^2' -o fit.json").exit_code, 0);
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"px4 --instance 4 -o p.params", "PX4 has the thermal compensation sets 0 to 3 of each sensor (TC_G0 to TC_G3"},
           {"px4 --instance -1 -o p.params", "--instance -1"},
           {"px4 --device-id 4294967296 -o p.params", "a 32-bit number"},
           {"px4 --boot-temp 20 -o p.params", "--boot-temp is ArduPilot's"},
           {"ardupilot --instance 0 -o a.param", "ArduPilot numbers its IMUs 1 to 5"},
           {"ardupilot --instance 6 -o a.param", "INS4_TCAL_, INS5_TCAL_"},
           {"ardupilot --device-id 5 -o a.param", "--device-id is PX4's"}})
    expect_refused(dir, "export fit.json --format " + args, expected);
  EXPECT_FALSE(std::filesystem::exists(dir / "p.params"));
  EXPECT_FALSE(std::filesystem::exists(dir / "a.param"));
  // A device id above 2^31 is written as the int32 PX4's parameter holds.
  ASSERT_EQ(run_cli(dir, "export fit.json --format px4 --instance 3 --device-id 4294967295 -o p.params").exit_code, 0);
  EXPECT_NE(slurp(dir / "p.params").find("TC_G3_ID\t-1\t6"), std::string::npos);
  // IMUs 4 and 5 have their own parameter groups.
  ASSERT_EQ(run_cli(dir, "export fit.json --format ardupilot --instance 4 -o a.param").exit_code, 0);
  const std::string a = slurp(dir / "a.param");
  EXPECT_NE(a.find("\nINS4_TCAL_ENABLE,1\n"), std::string::npos) << a;
  EXPECT_NE(a.find("\nINS4_TCAL_GYR3_Z,"), std::string::npos) << a;
  EXPECT_EQ(a.find("INS_TCAL4"), std::string::npos) << a;
}

}  // namespace
}  // namespace gyrotherm::studies
