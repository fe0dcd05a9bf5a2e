// `gyrotherm check` (studies/check/check_run.h): a calibration exported from a
// fit on one simulated run, checked on a second run of the same gyro, equal
// to the firmware's rule written here from the firmware sources
// (parameter_files.h); --max-residual passes a right model and fails a wrong
// one; each failure mode triggered by a log made for it and not by a clean
// one; bad parameter files refused.

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <map>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "cli_runner.h"
#include "imu_logs.h"
#include "parameter_files.h"
#include "studies/check/check_run.h"

namespace gyrotherm::testing {
namespace {

// The gyro's bias per axis (°/h), a quadratic in temperature.
double bias_dph(int axis, double temp_c) {
  const double d = temp_c - 30.0;
  return (axis == 0 ? 100.0 : axis == 1 ? -60.0 : 20.0) + (2.0 - axis) * d + 0.1 * d * d * (axis == 1 ? -1.0 : 1.0);
}

struct Thermal {
  double from_c = 10.0, to_c = 60.0;
  unsigned seed = 1;
  bool whole_degrees = false;
  double turn_share = 0.0;  // the share of samples (from the middle) with a tilted accelerometer
  double spin_dps = 0.0;    // a rotation about Z on those samples
};

// 2 h at 1 Hz, the temperature ramping from_c → to_c, white noise 30 °/h.
std::vector<ImuSample> run_samples(const Thermal& run) {
  std::mt19937_64 rng(run.seed);
  std::normal_distribution<double> noise(0.0, 30.0);
  std::vector<ImuSample> out;
  const int n = 7200;
  for (int k = 0; k < n; ++k) {
    double temp = run.from_c + (run.to_c - run.from_c) * k / (n - 1);
    if (run.whole_degrees) temp = std::round(temp);
    double rate[3];
    for (int a = 0; a < 3; ++a) rate[a] = (bias_dph(a, temp) + noise(rng)) * kDphToRadS;
    ImuSample s{static_cast<std::uint64_t>(k) * 1000000 + 2000000, static_cast<float>(temp), static_cast<float>(rate[0]),
                static_cast<float>(rate[1]), static_cast<float>(rate[2])};
    if (std::abs(k - n / 2) < run.turn_share * n / 2) {
      s.ax = 0.5f * 9.80665f;
      s.az = -0.866f * 9.80665f;
      s.z += static_cast<float>(run.spin_dps * 3.14159265358979 / 180.0);
    }
    out.push_back(s);
  }
  return out;
}

nlohmann::json check_json(const ScratchDir& dir, const std::string& args, int exit_code = 0) {
  const CliResult r = run_cli(dir, "check " + args + " --json");
  EXPECT_EQ(r.exit_code, exit_code) << args << "\n" << r.err;
  return r.out.empty() ? nlohmann::json() : nlohmann::json::parse(r.out);
}

std::vector<std::string> issues_of(const nlohmann::json& j) {
  std::vector<std::string> out;
  for (const auto& f : j["findings"]) out.push_back(f["issue"]);
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

// Windows of w s from the first sample, std of their means (as check computes its instability).
double instability(const std::vector<double>& t, const std::vector<double>& v, double w) {
  std::vector<double> means;
  double sum = 0.0;
  int n = 0, current = 0;
  for (std::size_t i = 0; i <= t.size(); ++i) {
    const int index = i < t.size() ? static_cast<int>(std::floor((t[i] - t[0]) / w)) : -1;
    if (index != current) {
      if (n >= 2) means.push_back(sum / n);
      sum = 0.0, n = 0, current = index;
    }
    if (i < t.size()) sum += v[i], ++n;
  }
  double mean = 0.0, ss = 0.0;
  for (const double m : means) mean += m / static_cast<double>(means.size());
  for (const double m : means) ss += (m - mean) * (m - mean);
  return std::sqrt(ss / static_cast<double>(means.size() - 1));
}

// The second run as the tests read it back: times, temperatures and rates (°/h) as logged (floats).
struct Logged {
  std::vector<double> t, temp;
  std::vector<std::vector<double>> rate{3};
};
Logged logged(const std::vector<ImuSample>& samples) {
  Logged l;
  for (const ImuSample& s : samples) {
    l.t.push_back(static_cast<double>(s.time_us) / 1e6);
    l.temp.push_back(s.temp_c);
    for (const auto& [a, v] : {std::pair{0, s.x}, {1, s.y}, {2, s.z}}) l.rate[a].push_back(static_cast<double>(v) / kDphToRadS);
  }
  return l;
}

// Two runs of the gyro as `write` logs them (run1.EXT, run2.EXT), the first
// fitted with `model` and exported with `export_args`; returns the second
// run's samples and the export's output in *exported.
template <class Write>
std::vector<ImuSample> fitted_and_exported(const ScratchDir& dir, Write write, const std::string& ext, Thermal first,
                                           Thermal second, const std::string& model, const std::string& export_args,
                                           CliResult* exported) {
  write(dir / ("run1." + ext), run_samples(first), LoggedParameters{});
  const std::vector<ImuSample> samples = run_samples(second);
  write(dir / ("run2." + ext), samples, LoggedParameters{});
  EXPECT_EQ(run_cli(dir, fmt::format("fit run1.{} --model '{}' -o fit.json", ext, model)).exit_code, 0);
  *exported = run_cli(dir, "export fit.json " + export_args);
  EXPECT_EQ(exported->exit_code, 0) << exported->err;
  return samples;
}

TEST(CliCheck, Px4ParametersOnASecondUlogAreAppliedAsPx4AppliesThem) {
  ScratchDir dir;
  CliResult exported;
  const std::vector<ImuSample> second =
      fitted_and_exported(dir, write_ulog, "ulg", {10.0, 60.0, 1}, {58.0, 15.0, 2}, "T + T^2",
                          fmt::format("--format px4 --device-id {} -o cal.params", kUlogDeviceId), &exported);
  // The run's temperature follows time (one ramp): a caution of meaning, carried into the file and said, not refused.
  EXPECT_NE(slurp(dir / "cal.params").find("# CAUTION: on the record the fit was made on, what these numbers mean is "
                                           "uncertain:\n#   gyro_x: T: temperature follows time"),
            std::string::npos)
      << slurp(dir / "cal.params");
  EXPECT_NE(exported.err.find("caution: gyro_x: T: temperature follows time"), std::string::npos) << exported.err;
  const nlohmann::json j = check_json(dir, "run2.ulg --params cal.params --max-residual 15");
  EXPECT_EQ(j["format"], "px4");
  EXPECT_EQ(j["calibration"], "TC_G0_");
  EXPECT_EQ(j["imu"], 1);  // paired by the device id, as PX4 pairs them
  EXPECT_EQ(j["passed"], true);
  // The file's own caution (temperature follows time on the fitted run) is carried, and nothing else is found.
  EXPECT_EQ(issues_of(j), (std::vector<std::string>{"calibration_caution"})) << j["findings"].dump();
  EXPECT_NE(j["findings"][0]["name"].get<std::string>().find("gyro_x: T: temperature follows time"), std::string::npos);
  // The run it was fitted on, given again: the file's provenance names it by its SHA-256.
  EXPECT_NE(slurp(dir / "cal.params").find("#   fitted on run1.ulg SHA-256 "), std::string::npos);
  const nlohmann::json own = check_json(dir, "run1.ulg --params cal.params");
  EXPECT_TRUE(has(issues_of(own), "fitted_log")) << own["findings"].dump();
  EXPECT_FALSE(has(issues_of(j), "fitted_log"));
  const std::map<std::string, float> p = read_qgc(slurp(dir / "cal.params"));
  const Logged l = logged(second);
  const double w = j["window_s"];
  ASSERT_EQ(w, 100.0);
  for (int a = 0; a < 3; ++a) {
    // PX4's rule from the firmware (parameter_files.h), on the same samples.
    fit::Measurement m;
    m.time_s = l.t, m.temp_c = l.temp, m.gyro_dph = l.rate[a];
    const std::vector<double> applied = px4_as_applied(m, p, a);
    std::vector<double> comp(l.t.size());
    for (std::size_t i = 0; i < comp.size(); ++i) comp[i] = l.rate[a][i] - applied[i];
    const nlohmann::json& x = j["axes"][a];
    EXPECT_NEAR(x["before_dph"].get<double>(), instability(l.t, l.rate[a], w), 1e-9 * instability(l.t, l.rate[a], w));
    EXPECT_NEAR(x["after_dph"].get<double>(), instability(l.t, comp, w), 1e-6 * instability(l.t, comp, w)) << a;
    // The compensation takes out the quadratic: what is left is near the noise of a 100 s mean, 30/√100 °/h.
    EXPECT_LT(x["after_dph"].get<double>(), 1.5 * 3.0) << a;
    EXPECT_GT(x["before_dph"].get<double>(), 4.0 * x["after_dph"].get<double>()) << a;
    EXPECT_LT(x["residual_dph"].get<double>(), 15.0) << a;
  }
}

TEST(CliCheck, MaxResidualFailsAModelThatMissesTheCurve) {
  ScratchDir dir;
  CliResult exported;
  fitted_and_exported(dir, write_ulog, "ulg", {10.0, 60.0, 3}, {58.0, 15.0, 4}, "T",
                      fmt::format("--format px4 --device-id {} -o line.params", kUlogDeviceId), &exported);
  // The quadratic's 0.1 °/h/°C² leaves tens of °/h about the line: exit 1, named per axis.
  const nlohmann::json j = check_json(dir, "run2.ulg --params line.params --max-residual 15", 1);
  EXPECT_EQ(j["passed"], false);
  EXPECT_GT(j["axes"][0]["residual_dph"].get<double>(), 30.0);
  EXPECT_TRUE(has(issues_of(j), "residual_over_limit"));
  // The limit in another unit: 15 °/h = 0.0041667 °/s.
  EXPECT_EQ(check_json(dir, "run2.ulg --params line.params --max-residual 0.0041667 --residual-unit dps", 1)["passed"], false);
  const CliResult text = run_cli(dir, "check run2.ulg --params line.params --max-residual 15");
  EXPECT_EQ(text.exit_code, 1);
  EXPECT_NE(text.out.find("verdict: FAIL"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("FAIL (every axis"), std::string::npos) << text.out;  // it does not say what PASS says
  // Without a limit, no verdict and exit 0.
  EXPECT_TRUE(check_json(dir, "run2.ulg --params line.params")["passed"].is_null());
  // A log too sparse for any temperature bin (15 samples over 50 °C): no
  // residual is shown (null, not 0), a finding says so per axis, and the limit is not passed.
  std::vector<ImuSample> sparse;
  const std::vector<ImuSample> full = run_samples({10.0, 60.0, 5});
  for (std::size_t k = 0; k < full.size(); k += 480) sparse.push_back(full[k]);
  write_ulog(dir / "sparse.ulg", sparse);
  const nlohmann::json none = check_json(dir, "sparse.ulg --params line.params --max-residual 15", 1);
  EXPECT_TRUE(none["axes"][0]["residual_dph"].is_null()) << none["axes"][0];
  EXPECT_TRUE(has(issues_of(none), "no_residual")) << none["findings"];
  EXPECT_FALSE(has(issues_of(none), "residual_over_limit")) << none["findings"];
  EXPECT_EQ(none["passed"], false);
  const CliResult sparse_text = run_cli(dir, "check sparse.ulg --params line.params");
  EXPECT_NE(sparse_text.out.find("this log cannot show the residual against temperature"), std::string::npos)
      << sparse_text.out;
}

TEST(CliCheck, ArduPilotParametersOnASecondDataFlashLogWithBootOffsets) {
  ScratchDir dir;
  CliResult exported;
  const std::vector<ImuSample> second = fitted_and_exported(dir, write_dataflash, "bin", {10.0, 60.0, 5}, {20.0, 50.0, 6},
                                                            "T + T^2", "--format ardupilot -o cal.parm", &exported);
  const nlohmann::json j = check_json(dir, "run2.bin --params cal.parm --max-residual 15");
  EXPECT_EQ(j["format"], "ardupilot");
  EXPECT_EQ(j["calibration"], "INS_TCAL1_");
  EXPECT_EQ(j["passed"], true);
  const std::map<std::string, float> p = read_ap(slurp(dir / "cal.parm"));
  const Logged l = logged(second);
  // Boot: the first 10 s, their mean rate the offsets, their mean temperature CALTEMP.
  std::size_t boot = 0;
  double boot_temp = 0.0;
  while (l.t[boot] - l.t[0] < 10.0) boot_temp += l.temp[boot++];
  boot_temp /= static_cast<double>(boot);
  EXPECT_NEAR(j["boot_c"].get<double>(), boot_temp, 1e-9);
  for (int a = 0; a < 3; ++a) {
    double offset = 0.0;
    for (std::size_t i = 0; i < boot; ++i) offset += l.rate[a][i] / static_cast<double>(boot);
    std::vector<double> comp(l.t.size());
    for (std::size_t i = 0; i < comp.size(); ++i)
      comp[i] = l.rate[a][i] - offset -
                ardupilot_subtracted(p, "XYZ"[a], static_cast<float>(l.temp[i]), static_cast<float>(boot_temp)) / kDphToRadS;
    EXPECT_NEAR(j["axes"][a]["after_dph"].get<double>(), instability(l.t, comp, 100.0), 1e-5 * instability(l.t, comp, 100.0));
    // The boot offsets take out the constant up to the noise of a 10 s mean (30/√10 °/h).
    double left = 0.0;
    for (const double c : comp) left += c / static_cast<double>(comp.size());
    EXPECT_NEAR(j["axes"][a]["offset_dph"].get<double>(), left, 1e-4) << a;
    EXPECT_LT(std::abs(left), 4.0 * 30.0 / std::sqrt(10.0)) << a;
  }
}

TEST(CliCheck, EachFailureModeIsFoundOnALogMadeForItAndNotOnACleanOne) {
  ScratchDir dir;
  // A hand-written ArduPilot calibration as its tempcal_IMU.py writes it ("NAME VALUE"), 28..34 °C.
  write_text(dir / "narrow.parm",
             "INS_TCAL1_ENABLE 1\nINS_TCAL1_TMIN 28.0\nINS_TCAL1_TMAX 34.0\n"
             "INS_TCAL1_GYR1_X 10.0\nINS_TCAL1_GYR2_X 0.0\nINS_TCAL1_GYR3_X 0.0\n");
  write_text(dir / "mid.parm",
             "# a calibration over 15 °C\nINS_TCAL1_TMIN,20\nINS_TCAL1_TMAX,35\nINS_TCAL1_GYR1_X,10\n"
             "INS_TCAL1_GYR2_X,0\nINS_TCAL1_GYR3_X,0\nINS_GYR_ID,2753028\n");
  write_dataflash(dir / "clean.bin", run_samples({20.0, 50.0, 7}));
  const nlohmann::json clean = check_json(dir, "clean.bin --params narrow.parm");
  // A hand-written set, not this gyro's: it takes little off any axis (Y and Z: nothing).
  EXPECT_EQ(issues_of(clean), (std::vector<std::string>{"calibration_span_minimum", "outside_range", "little_gain",
                                                        "little_gain", "little_gain"}));
  for (const auto& f : clean["findings"])
    if (f["issue"] == "little_gain") {
      EXPECT_GT(f["value"].get<double>(), studies::kLittleGain) << f;
      EXPECT_LE(f["value"].get<double>(), studies::kMadeWorse) << f;
    }
  // One that adds a slope of 1e-3 rad/s per °C (206 °/h per °C) over the whole run: worse
  // than no calibration, and not a pass however loose the residual limit.
  write_text(dir / "wrong.parm",
             "INS_TCAL1_ENABLE 1\nINS_TCAL1_TMIN 20.0\nINS_TCAL1_TMAX 50.0\n"
             "INS_TCAL1_GYR1_X 1000.0\nINS_TCAL1_GYR2_X 0.0\nINS_TCAL1_GYR3_X 0.0\n");
  const nlohmann::json wrong = check_json(dir, "clean.bin --params wrong.parm --max-residual 1e6", 1);
  EXPECT_EQ(wrong["passed"], false) << wrong["findings"];
  bool worse = false;
  for (const auto& f : wrong["findings"])
    if (f["issue"] == "made_worse") {
      worse = true;
      EXPECT_EQ(f["name"], "X") << f;
      EXPECT_GT(f["value"].get<double>(), 10.0) << f;
    }
  EXPECT_TRUE(worse) << wrong["findings"];
  EXPECT_TRUE(has(issues_of(check_json(dir, "clean.bin --params mid.parm")), "calibration_span_advice"));
  write_dataflash(dir / "enabled.bin", run_samples({20.0, 50.0, 7}), {{"INS_TCAL1_ENABLE", 1.0f}, {"INS_GYR_ID", 2753029.0f}});
  const std::vector<std::string> enabled = issues_of(check_json(dir, "enabled.bin --params mid.parm"));
  EXPECT_TRUE(has(enabled, "already_enabled"));
  EXPECT_TRUE(has(enabled, "device_mismatch"));
  for (const auto& f : check_json(dir, "enabled.bin --params mid.parm")["findings"])
    if (f["issue"] == "device_mismatch") {  // the log's id as data, and as the words
      ASSERT_EQ(f["devices"].size(), 1u);
      EXPECT_EQ(f["devices"][0]["device_id"], 2753029);
      EXPECT_EQ(f["devices"][0]["parameter"], "INS_GYR_ID");
      EXPECT_EQ(f["name"], "INS_GYR_ID 2753029");
    }
  write_dataflash(dir / "flat.bin", run_samples({30.0, 33.0, 8}));
  EXPECT_TRUE(has(issues_of(check_json(dir, "flat.bin --params narrow.parm")), "log_span_minimum"));
  Thermal quantised{20.0, 50.0, 9};
  quantised.whole_degrees = true;
  write_dataflash(dir / "whole.bin", run_samples(quantised));
  EXPECT_TRUE(has(issues_of(check_json(dir, "whole.bin --params narrow.parm")), "temperature_quantised"));
  Thermal tilted{20.0, 50.0, 10};
  tilted.turn_share = 0.1;
  write_dataflash(dir / "tilted.bin", run_samples(tilted));
  const nlohmann::json tilt = check_json(dir, "tilted.bin --params narrow.parm");
  ASSERT_TRUE(has(issues_of(tilt), "moving"));
  for (const auto& f : tilt["findings"]) {
    if (f["issue"] == "moving") {
      EXPECT_EQ(f["name"], "accelerometer");
    }
  }
  Thermal spun{20.0, 50.0, 11};
  spun.turn_share = 0.05;
  spun.spin_dps = 30.0;
  write_ulog(dir / "spun.ulg", run_samples(spun), {{"TC_G_ENABLE", 1.0f}});
  write_text(dir / "other.params",
             "# Onboard parameters for Vehicle 1\n1\t1\tTC_G0_ID\t12345\t6\n1\t1\tTC_G0_TMIN\t10\t9\n1\t1\tTC_G0_TMAX\t60\t9\n"
             "1\t1\tTC_G0_TREF\t35\t9\n1\t1\tTC_G0_X0_2\t0\t9\n1\t1\tTC_G0_X1_2\t0\t9\n1\t1\tTC_G0_X2_2\t0\t9\n"
             "1\t1\tTC_G0_X3_2\t0\t9\n");
  const nlohmann::json px4 = check_json(dir, "spun.ulg --params other.params");
  const std::vector<std::string> found = issues_of(px4);
  EXPECT_TRUE(has(found, "moving"));
  EXPECT_TRUE(has(found, "already_enabled"));
  EXPECT_TRUE(has(found, "device_mismatch"));
  for (const auto& f : px4["findings"])
    if (f["issue"] == "device_mismatch") {  // both of the log's gyros, each with its instance
      EXPECT_EQ(f["value"], 12345);
      ASSERT_EQ(f["devices"].size(), 2u);
      EXPECT_EQ(f["devices"][1]["device_id"], kUlogDeviceId);
      EXPECT_EQ(f["devices"][1]["instance"], 1);
      EXPECT_NE(f["name"].get<std::string>().find(std::to_string(kUlogDeviceId) + " (instance 1)"), std::string::npos);
    }
  EXPECT_EQ(px4["axes"].size(), 3u);
  EXPECT_EQ(px4["axes"][0]["after_dph"], px4["axes"][0]["before_dph"]);  // no X parameters: X left as it is
  // A log that cannot test the calibration (moving, corrected already, another gyro) does not pass,
  // however loose the limit; the advice alone (a narrow span, a flat log) leaves the verdict to the residual.
  for (const char* log : {"spun.ulg --params other.params", "enabled.bin --params mid.parm",
                          "tilted.bin --params narrow.parm"}) {
    const nlohmann::json judged = check_json(dir, std::string(log) + " --max-residual 1e6", 1);
    EXPECT_EQ(judged["passed"], false) << log << ": " << judged["findings"];
  }
  EXPECT_EQ(check_json(dir, "flat.bin --params narrow.parm --max-residual 1e6")["passed"], true);
}

TEST(CliCheck, AFitFileIsCheckedAsCompensateAppliesIt) {
  ScratchDir dir;
  write_ulog(dir / "run1.ulg", run_samples({10.0, 60.0, 12}));
  write_ulog(dir / "run2.ulg", run_samples({58.0, 15.0, 13}));
  ASSERT_EQ(run_cli(dir, "fit run1.ulg --model 'T + T^2' -o fit.json").exit_code, 0);
  const nlohmann::json j = check_json(dir, "run2.ulg --params fit.json --max-residual 15");
  EXPECT_EQ(j["format"], "fit");
  ASSERT_EQ(j["axes"].size(), 3u);
  EXPECT_EQ(j["axes"][2]["axis"], "gyro_z");
  EXPECT_EQ(j["passed"], true);
  for (int a = 0; a < 3; ++a) EXPECT_LT(j["axes"][a]["after_dph"].get<double>(), 1.5 * 3.0) << a;
  // The model's constant is the bias: nothing is left but noise.
  EXPECT_LT(std::abs(j["axes"][0]["offset_dph"].get<double>()), 3.0);
  const auto fitted_log = [](const nlohmann::json& check) {
    for (const auto& f : check["findings"])
      if (f["issue"] == "fitted_log") return true;
    return false;
  };
  EXPECT_FALSE(fitted_log(j)) << j["findings"];
  // The fit file knows the bytes it was fitted on: the same log given again
  // is found (by content, not name), and the text says what its PASS means.
  const nlohmann::json fit = nlohmann::json::parse(testing::slurp(dir.path() / "fit.json"));
  EXPECT_EQ(fit["channels"][0]["data"]["sha256"].get<std::string>().size(), 64u);
  const CliResult printed = run_cli(dir, "fit run1.ulg --model 'T + T^2' --json");
  EXPECT_EQ(nlohmann::json::parse(printed.out)["channels"][0]["data"]["sha256"], fit["channels"][0]["data"]["sha256"]);
  std::filesystem::copy_file(dir.path() / "run1.ulg", dir.path() / "copy.ulg");
  const nlohmann::json same = check_json(dir, "copy.ulg --params fit.json --max-residual 15", 1);
  EXPECT_TRUE(fitted_log(same)) << same["findings"];
  const CliResult text = run_cli(dir, "check copy.ulg --params fit.json");
  EXPECT_NE(text.out.find("finding: this log is the one the calibration was fitted on (run1.ulg"), std::string::npos)
      << text.out;
  // Its own residual is no production test: no PASS (the second run passed above).
  EXPECT_EQ(same["passed"], false) << same["findings"];
}

// One glitch moves a 100 s instability by a quarter on the cycle: check
// keeps it (as a firmware would), compensate's figure leaves it out. Both say
// so, and each figure is what its own samples give.
TEST(CliCheck, CheckAndCompensateSayHowTheirInstabilitiesTreatGlitches) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "--seed 7", "c.csv");
  ASSERT_EQ(run_cli(dir, "fit c.csv -o fit.json").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "compensate c.csv --fit fit.json -o comp.csv").exit_code, 0);
  // The compensated file's samples, 100 s means with and without the rows marked outlier.
  const std::string text = slurp(dir / "comp.csv");
  std::istringstream lines(text);
  std::string head, line;
  std::getline(lines, head);
  std::getline(lines, line);  // the column names
  std::map<long, std::pair<double, int>> all, clean;
  std::size_t flagged = 0;
  while (std::getline(lines, line)) {
    double t = 0, temp = 0, gyro = 0, model = 0, comp = 0;
    int outlier = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%d", &t, &temp, &gyro, &model, &comp, &outlier), 6) << line;
    const long w = static_cast<long>(std::floor(t / 100.0));
    all[w].first += comp;
    ++all[w].second;
    if (outlier == 0) {
      clean[w].first += comp;
      ++clean[w].second;
    }
    flagged += outlier != 0;
  }
  const auto instability = [](const std::map<long, std::pair<double, int>>& windows) {
    std::vector<double> means;
    for (const auto& [w, sum] : windows) means.push_back(sum.first / sum.second);
    double mean = 0, var = 0;
    for (double m : means) mean += m / static_cast<double>(means.size());
    for (double m : means) var += (m - mean) * (m - mean) / static_cast<double>(means.size() - 1);
    return std::sqrt(var);
  };
  ASSERT_GT(flagged, 0u) << "the seed should give the cycle a glitch";
  EXPECT_NE(head.find(fmt::format("(window averages without {} glitch", flagged)), std::string::npos) << head;
  const nlohmann::json fit = nlohmann::json::parse(run_cli(dir, "compensate c.csv --fit fit.json --json").out);
  // (The figure is of the window means less the model at the window; the file's rows hold the model
  // interpolated to each sample: the two agree to a few parts in 10⁴.)
  EXPECT_NEAR(instability(clean), fit["instability_after_dph"].get<double>(), 1e-3 * instability(clean));
  const nlohmann::json j = check_json(dir, "c.csv --params fit.json");
  EXPECT_EQ(j["glitches_flagged"], flagged);
  EXPECT_NEAR(instability(all), j["axes"][0]["after_dph"].get<double>(), 1e-3 * instability(all));
  EXPECT_GT(instability(all), 1.01 * instability(clean));  // the glitch's part, well beyond the tolerance
  const CliResult said = run_cli(dir, "check c.csv --params fit.json");
  EXPECT_NE(said.out.find(fmt::format("the {} the fit's glitch rule flags too", flagged)), std::string::npos) << said.out;
}

TEST(CliCheck, BadParameterFilesAreRefusedNamingTheLine) {
  ScratchDir dir;
  write_ulog(dir / "run.ulg", run_samples({20.0, 50.0, 14}));
  write_text(dir / "words.parm", "INS_TCAL1_TMIN 20\nthis is not a parameter\n");
  expect_refused(dir, "check run.ulg --params words.parm", "words.parm:2: expected a parameter line");
  write_text(dir / "twice.parm", "INS_TCAL1_TMIN 20\nINS_TCAL1_TMIN 21\n");
  expect_refused(dir, "check run.ulg --params twice.parm", "twice.parm:2: INS_TCAL1_TMIN given again");
  write_text(dir / "none.parm", "ATC_RAT_RLL_P 0.1\n");
  expect_refused(dir, "check run.ulg --params none.parm", "it holds no gyro thermal parameters");
  write_text(dir / "nan.parm", "INS_TCAL1_TMIN nan\n");
  expect_refused(dir, "check run.ulg --params nan.parm", "nan.parm:1: INS_TCAL1_TMIN: 'nan' is not a finite number");
  write_text(dir / "part.parm", "INS_TCAL1_TMIN 20\nINS_TCAL1_GYR1_X 1\n");
  expect_refused(dir, "check run.ulg --params part.parm", "INS_TCAL1_TMAX is missing");
  expect_refused(dir, "check run.ulg --params absent.parm", "absent.parm: cannot open");
  write_text(dir / "ok.parm", "INS_TCAL1_TMIN 20\nINS_TCAL1_TMAX 50\nINS_TCAL1_GYR1_X 1\nINS_TCAL1_GYR2_X 0\nINS_TCAL1_GYR3_X 0\n");
  expect_refused(dir, "check run.ulg --params ok.parm --max-residual -1", "--max-residual -1");
  expect_refused(dir, "check run.ulg --params ok.parm --max-residual 1 --residual-unit furlongs", "--residual-unit");
  expect_refused(dir, "check run.ulg --params ok.parm --avg 0", "--avg 0: expected a window of more than 0 s");
  expect_refused(dir, "check run.ulg --params ok.parm --boot -1", "--boot -1: expected more than 0 s");
  expect_refused(dir, "check run.ulg --params ok.parm --imu -1", "--imu -1: expected an instance of 0 or more");
}

}  // namespace
}  // namespace gyrotherm::testing
