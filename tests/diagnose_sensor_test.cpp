// diagnose on another sensor than a gyro (studies/diagnose with
// fit/data/sensor_kind.h): the simulated MEMS IMU's accelerometer z axis,
// whose true bias holds a T³ term, fitted with T + T² from its PX4 ULog:
// diagnose puts T³ first (the record cannot tell the higher powers apart by
// their regressors, so it names the group), its coefficient's interval
// holds the truth, and everything it says (text, JSON, figures) is in m/s²;
// an axis whose model is complete is given no term; no plan next step is
// offered (plan designs a gyro's test only). An accelerometer that drifts
// with time is told to add t, by a next command that reads it as one.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace gyrotherm::studies {
namespace {

using testing::CliResult, testing::run_cli, testing::ScratchDir, testing::source_path;

TEST(DiagnoseSensor, AnAccelerometersMissingCubicIsFoundInItsUnits) {
  ScratchDir dir;
  ASSERT_EQ(run_cli(dir, "simulate " + source_path("scenarios/imu.toml") + " -o imu.ulg").exit_code, 0);
  const std::string args = "diagnose imu.ulg --sensor accel --gyro-col accel_z --model 'T + T^2'";
  const CliResult r = run_cli(dir, args + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sensor"], "accel");
  EXPECT_EQ(j["unit"], "m/s²");
  const std::string kind = j["verdict_data"]["kind"];
  ASSERT_TRUE(kind == "found" || kind == "group") << j["verdict"];
  const nlohmann::json named = kind == "found" ? j["verdict_data"]["terms"] : j["verdict_data"]["group"];
  EXPECT_NE(std::find(named.begin(), named.end(), "T^3"), named.end()) << j["verdict"];
  const nlohmann::json& top = j["missing_effects"][0];
  EXPECT_EQ(top["term"], "T^3");
  EXPECT_LE(top["coefficient_interval_95"][0].get<double>(), 1e-7);  // the truth (scenarios/imu_gyro.toml)
  EXPECT_GE(top["coefficient_interval_95"][1].get<double>(), 1e-7);
  EXPECT_EQ(j["plan_command"], "");
  EXPECT_NE(j["noise_model_found"]["components"].dump().find("vrw"), std::string::npos);

  const CliResult text = run_cli(dir, args + " --plots figures");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("m/s² per °C³"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("noise floor"), std::string::npos);
  EXPECT_EQ(text.out.find("°/h"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("gyrotherm plan"), std::string::npos) << text.out;
  for (const char* png : {"bias_time.png", "residual_vs.png", "allan.png"})
    EXPECT_TRUE(std::filesystem::exists(dir / "figures" / png)) << png;

  // A simulated CSV's truth columns are never tried as causes.
  ASSERT_EQ(run_cli(dir, "simulate " + source_path("scenarios/imu.toml") + " -o imu.csv").exit_code, 0);
  const CliResult csv = run_cli(dir, "diagnose imu.csv --sensor accel --gyro-col accel_z_mps2 --model 'T + T^2 + T^3' --json");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const nlohmann::json jc = nlohmann::json::parse(csv.out);
  for (const auto& c : jc["columns_tried"]) EXPECT_EQ(c.get<std::string>().find("true"), std::string::npos) << c;
  for (const auto& e : jc["missing_effects"]) EXPECT_EQ(e["term"].get<std::string>().find("true"), std::string::npos) << e["term"];
  EXPECT_NE(jc["skipped"].dump().find("truth's or compensation's column"), std::string::npos) << jc["skipped"];

  // The y axis, whose truth is T + T², is given nothing to add.
  const CliResult y = run_cli(dir, "diagnose imu.ulg --sensor accel --gyro-col accel_y --model 'T + T^2' --json");
  ASSERT_EQ(y.exit_code, 0) << y.err;
  EXPECT_EQ(nlohmann::json::parse(y.out)["verdict_data"]["kind"], "none") << nlohmann::json::parse(y.out)["verdict"];
}

TEST(DiagnoseSensor, AnAccelerometerThatDriftsIsToldToAddTimeByACommandThatReadsItAsOne) {
  ScratchDir dir;
  testing::write_text(dir / "drift.toml", "[truth]\nb0_dph = 1.0\n[[channel]]\nsensor = \"accel\"\naxis = \"x\"\n"
                                          "b0 = 0.05\nwhite_noise = 0.002\nterms = { T = 2e-3, t = 5e-4 }\n");
  ASSERT_EQ(run_cli(dir, "simulate " + source_path("scenarios/imu.toml") + " --gyro drift.toml -o d.csv").exit_code, 0);
  const CliResult r = run_cli(dir, "diagnose d.csv --sensor accel --gyro-col accel_x_mps2 --model T --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["verdict_data"]["kind"], "found") << j["verdict"];
  EXPECT_EQ(j["verdict_data"]["terms"], nlohmann::json::array({"t"}));
  const nlohmann::json& t = j["missing_effects"][0];
  EXPECT_LE(t["coefficient_interval_95"][0].get<double>(), 5e-4);  // m/s² per hour, the truth
  EXPECT_GE(t["coefficient_interval_95"][1].get<double>(), 5e-4);
  const std::string next = j["next_command"];
  EXPECT_NE(next.find("--sensor accel"), std::string::npos) << next;
  EXPECT_NE(next.find("--gyro-col accel_x_mps2"), std::string::npos) << next;
  EXPECT_EQ(run_cli(dir, next.substr(std::string("gyrotherm ").size())).exit_code, 0) << next;
}

}  // namespace
}  // namespace gyrotherm::studies
