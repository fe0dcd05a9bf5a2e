// `gyrotherm report` (studies/report/report.h): the page's every number is
// its JSON twin's at the pointer its cell names; the twin's fit and diagnosis
// are `fit --json` and `diagnose --json` on the same input; the page is self-
// contained (no URL leaves it); a log the tool refuses leaves neither file.
// (The page in a real browser: tests/python/test_report_browser.py.)

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <regex>
#include <string>

#include "cli_runner.h"
#include "imu_logs.h"

namespace gyrotherm::testing {
namespace {

using Json = nlohmann::json;

// Each <td … data-json="POINTER">TEXT</td> of the page against the twin.
void expect_cells_match(const std::string& html, const Json& twin) {
  const std::regex cell(R"re(data-json="([^"]+)">([^<]*)<)re");
  std::size_t n = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), cell); it != std::sregex_iterator(); ++it, ++n) {
    const std::string pointer = (*it)[1], text = (*it)[2];
    const Json::json_pointer p(pointer);
    if (!twin.contains(p) || !twin.at(p).is_number()) {
      EXPECT_EQ(text, "—") << pointer;
      continue;
    }
    EXPECT_EQ(text, twin.at(p).is_number_integer() ? twin.at(p).dump() : fmt::format("{:.6g}", twin.at(p).get<double>()))
        << pointer;
  }
  EXPECT_GT(n, 20u);
}

TEST(CliReport, ThePageIsItsTwinAndTheTwinIsTheCommandsJson) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", " --hidden grad=0.02", "grad.csv");
  ASSERT_EQ(run_cli(dir, "fit grad.csv -o fit.json").exit_code, 0);
  const CliResult r = run_cli(dir, "report grad.csv --fit fit.json -o report.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("diagnosing"), std::string::npos) << r.err;  // progress on stderr
  const std::string html = slurp(dir / "report.html");
  const Json twin = Json::parse(slurp(dir / "report.json"));
  expect_cells_match(html, twin);
  // The twin holds the commands' own JSON.
  const Json fit = Json::parse(slurp(dir / "fit.json"));
  EXPECT_EQ(twin["channels"][0]["fit"]["coefficients"], fit["coefficients"]);
  const Json diagnosis = Json::parse(run_cli(dir, "diagnose grad.csv --json").out);
  EXPECT_EQ(twin["channels"][0]["diagnosis"]["verdict"], diagnosis["verdict"]);
  EXPECT_EQ(twin["channels"][0]["diagnosis"]["missing_effects"][0]["term"], "grad");
  EXPECT_NE(html.find(diagnosis["verdict"].get<std::string>().substr(0, 40)), std::string::npos);
  // What the record cannot tell apart, from diagnose's groups.
  const Json& groups = diagnosis["confounded"];
  ASSERT_FALSE(groups.empty());
  EXPECT_NE(html.find("cannot tell apart (terms that explain the same part of the bias here): " +
                      groups[0][0].get<std::string>() + " / " + groups[0][1].get<std::string>()),
            std::string::npos);
  const Json compensated = Json::parse(run_cli(dir, "compensate grad.csv --fit fit.json --json").out);
  EXPECT_EQ(twin["channels"][0]["compensate"]["instability_after_dph"], compensated["instability_after_dph"]);
  EXPECT_EQ(twin["log"]["sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(twin["log"]["sensors"]["format"], "text table");
  // The fit is this record's: the model's band (its coverage over seeds:
  // tests/model_band_test.cpp), with the dof its t took.
  const Json& band = twin["channels"][0]["band"];
  EXPECT_TRUE(band["missing"].is_null());
  EXPECT_GT(band["half_width_dph"][0].get<double>(), 0.0);
  EXPECT_GE(band["half_width_dph"][1].get<double>(), band["half_width_dph"][0].get<double>());
  EXPECT_GE(band["dof"].get<double>(), 1.0);
  // dT is no power of T: the firmwares cannot store this model, and the page says which term.
  EXPECT_EQ(twin["channels"][0]["firmware"]["expressible"], false);
  EXPECT_EQ(twin["channels"][0]["firmware"]["not_expressible"][0], "dT");
  EXPECT_NE(html.find("this model's dT cannot be stored"), std::string::npos);
  // A fit from another record brings no band of this one's.
  simulate_shipped(dir, "cycle", " --seed 7", "other.csv");
  ASSERT_EQ(run_cli(dir, "report other.csv --fit fit.json -o other.html").exit_code, 0);
  EXPECT_EQ(Json::parse(slurp(dir / "other.json"))["channels"][0]["band"]["missing"], "other_record");
  EXPECT_NE(slurp(dir / "other.html").find("the fit was made on another record"), std::string::npos);
  // Read in one pass (as a log too large to hold is), the page counts the same samples.
  const CliResult streamed = run_shell(dir, std::string("GYROTHERM_STREAM_ABOVE_MB=0 '") + GYROTHERM_CLI +
                                                "' report grad.csv --fit fit.json -o streamed.html");
  ASSERT_EQ(streamed.exit_code, 0) << streamed.err;
  EXPECT_EQ(Json::parse(slurp(dir / "streamed.json"))["log"]["samples"], twin["log"]["samples"]);
  // Self-contained: four figures embedded, nothing fetched.
  std::size_t images = 0;
  for (std::size_t at = html.find("src=\"data:image/png;base64,"); at != std::string::npos;
       at = html.find("src=\"data:image/png;base64,", at + 1))
    ++images;
  EXPECT_EQ(images, 4u);
  EXPECT_EQ(html.find("http://"), std::string::npos);
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_NE(html.find("@media print"), std::string::npos);
}

TEST(CliReport, ARoundTripOnAUlogWithACheckAndAFitMadeHere) {
  ScratchDir dir;
  std::vector<ImuSample> samples;
  for (int k = 0; k < 7200; ++k) {
    const double temp = 15.0 + 40.0 * k / 7199.0, d = temp - 30.0;
    const double rate = (100.0 + 2.0 * d + 0.1 * d * d + 20.0 * std::sin(0.37 * k)) * 3.14159265358979 / 648000.0;
    samples.push_back({static_cast<std::uint64_t>(k) * 1000000 + 1000000, static_cast<float>(temp),
                       static_cast<float>(rate), static_cast<float>(-rate), static_cast<float>(0.5 * rate)});
  }
  write_ulog(dir / "run.ulg", samples);
  write_dataflash(dir / "run.bin", samples);
  // The DataFlash log of the same samples gives the same page's numbers (the date aside).
  ASSERT_EQ(run_cli(dir, "report run.bin --model 'T + T^2' -o bin.html").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "report run.ulg --model 'T + T^2' -o ulg.html").exit_code, 0);
  Json bin = Json::parse(slurp(dir / "bin.json")), ulg = Json::parse(slurp(dir / "ulg.json"));
  EXPECT_EQ(bin["channels"][1]["fit"]["coefficients"], ulg["channels"][1]["fit"]["coefficients"]);
  EXPECT_EQ(bin["channels"][1]["allan"]["series"][1]["adev_dph"], ulg["channels"][1]["allan"]["series"][1]["adev_dph"]);
  ASSERT_EQ(run_cli(dir, "fit run.ulg --model 'T + T^2' -o fit.json").exit_code, 0);
  ASSERT_EQ(run_cli(dir, fmt::format("export fit.json --format px4 --device-id {} -o cal.params", kUlogDeviceId)).exit_code, 0);
  const CliResult r = run_cli(dir, "report run.ulg --model 'T + T^2' --params cal.params --max-residual 20 -o r.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json twin = Json::parse(slurp(dir / "r.json"));
  ASSERT_EQ(twin["channels"].size(), 3u);
  // The header names the log's gyro by its device id.
  EXPECT_EQ(twin["log"]["sensors"]["format"], "ULog v1");
  ASSERT_EQ(twin["log"]["sensors"]["gyros"].size(), 2u);  // instance 0 has no temperature: 1 is read
  EXPECT_EQ(twin["log"]["sensors"]["gyros"][0]["read"], false);
  EXPECT_EQ(twin["log"]["sensors"]["gyros"][1]["device_id"], kUlogDeviceId);
  EXPECT_EQ(twin["log"]["sensors"]["gyros"][1]["read"], true);
  // The model in the firmware's units is what export wrote, each inside its interval.
  const std::string params = slurp(dir / "cal.params");
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const Json& px4 = twin["channels"][axis]["firmware"]["px4"];
    for (int k = 0; k < 4; ++k) {
      const std::smatch m = [&] {
        std::smatch found;
        const std::regex line(fmt::format(R"(TC_G0_X{}_{}\t([-+0-9.eE]+))", k, axis));
        std::regex_search(params, found, line);
        return found;
      }();
      ASSERT_FALSE(m.empty()) << k << " " << axis;
      const double exported = std::stod(m[1]), value = px4["values"][k].get<double>();
      EXPECT_NEAR(value, exported, 1e-6 * std::abs(exported) + 1e-12) << "X" << k << " axis " << axis;
      EXPECT_LE(px4["intervals_95"][k][0].get<double>(), value);
      EXPECT_GE(px4["intervals_95"][k][1].get<double>(), value);
    }
    // The top power's coefficient does not move with the reference: ArduPilot's
    // T² (about 35 °C, ×10⁶) is PX4's (about TREF), value and half width; the
    // cubic is zero and exact.
    const Json& ap = twin["channels"][axis]["firmware"]["ardupilot"];
    const auto half = [](const Json& block, int k) {
      return 0.5 * (block["intervals_95"][k][1].get<double>() - block["intervals_95"][k][0].get<double>());
    };
    const double x2 = px4["values"][2].get<double>();
    EXPECT_NEAR(ap["values"][1].get<double>(), 1e6 * x2, 1e-6 * std::abs(1e6 * x2)) << "axis " << axis;
    EXPECT_GT(half(px4, 2), 0.0);
    EXPECT_NEAR(half(ap, 1), 1e6 * half(px4, 2), 1e-9 * 1e6 * half(px4, 2)) << "axis " << axis;
    EXPECT_EQ(px4["values"][3].get<double>(), 0.0);
    EXPECT_EQ(half(px4, 3), 0.0);
    EXPECT_EQ(half(ap, 2), 0.0);
  }
  EXPECT_EQ(twin["channels"][2]["channel"], "gyro_z");
  EXPECT_EQ(twin["check"]["format"], "px4");
  EXPECT_EQ(twin["passed"], true);
  const std::string html = slurp(dir / "r.html");
  expect_cells_match(html, twin);
  EXPECT_NE(html.find("PASS"), std::string::npos);
  ASSERT_EQ(twin["limits"].size(), 1u);
  EXPECT_EQ(twin["limits"][0]["name"], "residual");
  // The user's limits, each judged: the 40 °C span passes 25 and fails 50.
  ASSERT_EQ(run_cli(dir, "report run.ulg --model 'T + T^2' --limits span=25,ratio=2 -o ok.html").exit_code, 0);
  const Json ok = Json::parse(slurp(dir / "ok.json"));
  EXPECT_EQ(ok["passed"], true);
  EXPECT_NEAR(ok["limits"][0]["value"].get<double>(), 40.0 - 80.0 * 49.5 / 7199.0, 0.01);  // of the 100 s window means
  ASSERT_EQ(run_cli(dir, "report run.ulg --model 'T + T^2' --limits span=50 -o no.html").exit_code, 0);
  const Json no = Json::parse(slurp(dir / "no.json"));
  EXPECT_EQ(no["passed"], false);
  EXPECT_NE(slurp(dir / "no.html").find("class=\"fail\">FAIL"), std::string::npos);
  expect_cells_match(slurp(dir / "no.html"), no);
}

TEST(CliReport, TheRealThreeAxisPanLogHasAPagePerAxis) {
  const std::string pan = source_path("../shared/data/real/pan_tvac/TVCtest3_7_20.csv");
  if (!std::filesystem::exists(pan)) GTEST_SKIP() << "no PAN thermal-vacuum log";
  ScratchDir dir;
  const CliResult r = run_cli(dir, "report " + pan + " --time-col 'time (ms)' --gyro-col 'gyrox rad/s,gyroy rad/s,gyroz rad/s' "
                                   "--gyro-scale 0.5 --temp-col temp --temp-scale 0.00390625 --temp-offset -231 "
                                   "--model 'T + T^2' -o pan.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json twin = Json::parse(slurp(dir / "pan.json"));
  ASSERT_EQ(twin["channels"].size(), 3u);
  EXPECT_EQ(twin["log"]["windows"], 25);  // one window per 5 s burst
  // It only cools: each channel's page says temperature follows time.
  for (const Json& c : twin["channels"]) EXPECT_TRUE(c["fit"]["record"]["flags"].contains("T")) << c["channel"];
  const std::string html = slurp(dir / "pan.html");
  expect_cells_match(html, twin);
  EXPECT_NE(html.find("temperature follows time"), std::string::npos);
  EXPECT_LT(html.size(), 2u << 20);
}

// The paper's random profile (75 h: holds, fast ramps, the chamber switched
// off): the page, its twin and its size as for the cycle.
TEST(CliReport, TheRandomProfileHasItsPage) {
  ScratchDir dir;
  simulate_shipped(dir, "random", "", "random.csv");
  const CliResult r = run_cli(dir, "report random.csv --model 'T + T^2 + dT' -o random.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(dir / "random.html");
  const Json twin = Json::parse(slurp(dir / "random.json"));
  expect_cells_match(html, twin);
  EXPECT_GT(twin["log"]["duration_h"].get<double>(), 70.0);
  EXPECT_GT(twin["log"]["span_c"].get<double>(), 60.0);
  EXPECT_TRUE(twin["channels"][0]["band"]["missing"].is_null());
  std::size_t images = 0;
  for (std::size_t at = html.find("src=\"data:image/png;base64,"); at != std::string::npos;
       at = html.find("src=\"data:image/png;base64,", at + 1))
    ++images;
  EXPECT_EQ(images, 4u);
  EXPECT_LT(html.size(), 2u << 20);
  const Json fit = Json::parse(run_cli(dir, "fit random.csv --model 'T + T^2 + dT' --json").out);
  EXPECT_EQ(twin["channels"][0]["fit"]["coefficients"], fit["coefficients"]);
}

TEST(CliReport, ARefusedLogOrRequestLeavesNothing) {
  ScratchDir dir;
  write_text(dir / "short.csv", "time_s,temp_c,gyro_dph\n0,20,1\n1,20,1\n2,20,1\n");
  expect_refused(dir, "report short.csv -o r.html", "short.csv");
  EXPECT_FALSE(std::filesystem::exists(dir / "r.html"));
  EXPECT_FALSE(std::filesystem::exists(dir / "r.json"));
  expect_refused(dir, "report short.csv -o r.pdf", "name it FILE.html");
  expect_refused(dir, "report short.csv --max-residual 3 -o r.html", "give it with --params");
  expect_refused(dir, "report short.csv --limits residual=3 -o r.html", "give it with --params");
  expect_refused(dir, "report short.csv --limits speed=3 -o r.html", "--limits 'speed=3': expected NAME=VALUE");
  expect_refused(dir, "report short.csv --limits span=-1 -o r.html", "--limits 'span=-1'");
  expect_refused(dir, "report short.csv --limits span=1,span=2 -o r.html", "span given twice");
  write_text(dir / "fit.json", "{}");
  expect_refused(dir, "report short.csv --fit fit.json --model T -o r.html", "--fit brings its own model");
  EXPECT_FALSE(std::filesystem::exists(dir / "r.html"));
  // The page's JSON twin beside the fit file of the same name would replace
  // it: refused, and the fit file is as it was.
  expect_refused(dir, "report short.csv --fit fit.json -o fit.html", "fit.json would be written over fit.json (--fit)");
  expect_refused(dir, "report short.csv --params ./fit.json -o fit.html", "(--params)");
  EXPECT_EQ(slurp(dir / "fit.json"), "{}");
  EXPECT_FALSE(std::filesystem::exists(dir / "fit.html"));
}

}  // namespace
}  // namespace gyrotherm::testing
