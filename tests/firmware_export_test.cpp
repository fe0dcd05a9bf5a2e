// `gyrotherm export --format px4|ardupilot` (studies/export/firmware, px4.cpp,
// ardupilot.cpp): the exported parameters re-evaluated with each firmware's
// own formula, written here from its source, against the fit's model.
//
// PX4: src/modules/temperature_compensation/TemperatureCompensation.cpp,
// calc_thermal_offsets_3D (float arithmetic, temperature clipped to
// [TMIN, TMAX], offset = x0 + x1 d + x2 d² + x3 d³, subtracted).
// ArduPilot: libraries/AP_InertialSensor/AP_InertialSensor_tempcal.cpp,
// TCal::polynomial_eval and correct_sensor (TEMP_REFERENCE 35, ×1e-6,
// v −= p(T − 35), v += p(T_cal − 35), both temperatures constrained).

#include "studies/export/firmware.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_runner.h"
#include "parameter_files.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;


struct Fitted {
  double c[4] = {0, 0, 0, 0};
  double tmin = 0, tmax = 0;
  double bias(double t) const { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); }  // °/h
};

Fitted read_fit(const nlohmann::json& j) {
  Fitted f;
  f.c[0] = j["coefficients"]["1"];
  for (const auto& [name, k] : {std::pair<const char*, int>{"T", 1}, {"T^2", 2}, {"T^3", 3}})
    if (j["coefficients"].contains(name)) f.c[k] = j["coefficients"][name];
  f.tmin = j["data"]["temp_range_c"][0];
  f.tmax = j["data"]["temp_range_c"][1];
  return f;
}

// A scenario and the polynomial its range supports (the warm-up's narrow,
// monotone range makes T, T², T³ collinear).
class FirmwareExport : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

// Every shipped scenario, a polynomial model: both firmwares give the model's
// bias inside the range to 1e-6 of it, and hold it at the edge outside.
TEST_P(FirmwareExport, FirmwareFormulasGiveTheModel) {
  ScratchDir dir;
  const auto& [scenario, model] = GetParam();
  simulate_shipped(dir, scenario, "", "d.csv");
  const auto fitted = run_cli(dir, "fit d.csv --model '" + model + "' -o fit.json");
  ASSERT_EQ(fitted.exit_code, 0) << fitted.err;
  const Fitted fit = read_fit(nlohmann::json::parse(slurp(dir / "fit.json")));
  ASSERT_LT(fit.tmin, fit.tmax);

  const auto px4 = run_cli(dir, "export fit.json --format px4 -o g.params");
  ASSERT_EQ(px4.exit_code, 0) << px4.err;
  const auto p = read_qgc(slurp(dir / "g.params"));
  EXPECT_EQ(p.at("TC_G_ENABLE"), 1.0f);
  EXPECT_FLOAT_EQ(p.at("TC_G0_TMIN"), static_cast<float>(fit.tmin));
  EXPECT_FLOAT_EQ(p.at("TC_G0_TMAX"), static_cast<float>(fit.tmax));
  const auto ap = run_cli(dir, "export fit.json --format ardupilot -o g.param");
  ASSERT_EQ(ap.exit_code, 0) << ap.err;
  const auto a = read_ap(slurp(dir / "g.param"));
  EXPECT_EQ(a.at("INS_TCAL1_ENABLE"), 1.0f);

  for (int i = 0; i <= 200; ++i) {
    const double t = fit.tmin - 20.0 + (fit.tmax - fit.tmin + 40.0) * i / 200.0;
    const double inside = std::clamp(t, fit.tmin, fit.tmax);
    const double truth = fit.bias(inside) * kDphToRadS;  // rad/s
    EXPECT_NEAR(px4_offset(p, 0, static_cast<float>(t)), truth, 1e-6 * std::abs(truth)) << "T = " << t;
    EXPECT_EQ(px4_offset(p, 1, static_cast<float>(t)), 0.0f);  // axes without a fit
    // ArduPilot: the boot calibration takes out the bias at T_cal (its
    // offsets), the parameters the change from there.
    for (const double cal : {fit.tmin + 3.0, 0.5 * (fit.tmin + fit.tmax)}) {
      const double subtracted = ardupilot_subtracted(a, 'X', static_cast<float>(t), static_cast<float>(cal)) +
                                fit.bias(cal) * kDphToRadS;
      EXPECT_NEAR(subtracted, truth, 1e-6 * std::abs(truth)) << "T = " << t << ", T_cal = " << cal;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenarios, FirmwareExport,
                         ::testing::Values(std::pair<std::string, std::string>{"cycle", "T + T^2 + T^3"},
                                           std::pair<std::string, std::string>{"random", "T + T^2 + T^3"},
                                           std::pair<std::string, std::string>{"warmup", "T + T^2"}));

TEST(FirmwareExportMath, ReexpansionIsExact) {
  // A cubic (every firmware's gyro) and a quintic (PX4's barometer).
  for (const std::array<double, 6>& c : {std::array<double, 6>{1.5, -0.25, 3e-3, -2e-5, 0.0, 0.0},
                                         std::array<double, 6>{1.5, -0.25, 3e-3, -2e-5, 4e-7, -3e-9}}) {
    PolynomialModel m;
    m.c = c;
    for (const double r : {-10.0, 0.0, 22.5, 35.0}) {
      const auto a = reexpand(m, r);
      if (c[5] == 0.0) {
        EXPECT_EQ(a[4], 0.0);
      }
      for (const double d : {-30.0, -1.0, 0.0, 2.5, 40.0})
        EXPECT_NEAR(a[0] + d * (a[1] + d * (a[2] + d * (a[3] + d * (a[4] + d * a[5])))), m.evaluate(r + d),
                    1e-12 * (1.0 + std::abs(m.evaluate(r + d))));
    }
  }
}

// Three channels to three axes, in the order --axes names them.
TEST(CliExport, AxesMapTheFitsChannels) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  write_columns(dir, "d.csv", "three.csv", {{"gx", "$6"}, {"gy", "-$6+0.001*$4*$4"}, {"gz", "0.5*$6"}});
  ASSERT_EQ(run_cli(dir, "fit three.csv --gyro-col gx,gy,gz --model 'T + T^2' -o fit.json").exit_code, 0);
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "fit.json"));
  const auto r = run_cli(dir, "export fit.json --format px4 --axes gz,-,gx --instance 1 --device-id 2293768 -o g.params");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = slurp(dir / "g.params");
  EXPECT_NE(text.find("TC_G1_ID\t2293768\t6"), std::string::npos) << text;
  std::map<std::string, float> p;
  for (const auto& [name, value] : read_qgc(text))  // instance 1 read as 0 by px4_offset
    p[name.rfind("TC_G1_", 0) == 0 ? "TC_G0_" + name.substr(6) : name] = value;
  const Fitted gx = read_fit(j["channels"][0]), gz = read_fit(j["channels"][2]);
  const double t = 0.5 * (gx.tmin + gx.tmax) + 7.0;
  EXPECT_NEAR(px4_offset(p, 0, static_cast<float>(t)), gz.bias(t) * kDphToRadS, 1e-6 * std::abs(gz.bias(t) * kDphToRadS));
  EXPECT_EQ(px4_offset(p, 1, static_cast<float>(t)), 0.0f);
  EXPECT_NEAR(px4_offset(p, 2, static_cast<float>(t)), gx.bias(t) * kDphToRadS, 1e-6 * std::abs(gx.bias(t) * kDphToRadS));
  expect_refused(dir, "export fit.json --format px4 --axes gx,gy -o none.params", "--axes gx,gy: expected three entries");
  expect_refused(dir, "export fit.json --format px4 --axes -,-,- -o none.params", "every axis is '-'");
  EXPECT_FALSE(std::filesystem::exists(dir / "none.params"));
  expect_refused(dir, "export fit.json --format px4 --axes gx,gq,- -o g.params", "'gq' is not a channel of fit.json (its channels: gx, gy, gz)");
}

TEST(CliExport, AModelTheFirmwareCannotExpressIsRefusedOrDroppedWithItsCost) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  ASSERT_EQ(run_cli(dir, "fit d.csv -o fit.json").exit_code, 0);  // T + T^2 + dT
  for (const char* format : {"px4", "ardupilot"}) {
    const auto refused = run_cli(dir, std::string("export fit.json --format ") + format + " -o out.txt");
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_NE(refused.err.find("a term (dT)"), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("--drop-unsupported"), std::string::npos) << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.txt"));
  }
  // Dropping needs the fitted data to say what it costs.
  run_shell(dir, "mv d.csv moved.csv");
  expect_refused(dir, "export fit.json --format px4 --drop-unsupported -o out.params", "give it with --data");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.params"));
  run_shell(dir, "mv moved.csv d.csv");
  const auto dropped = run_cli(dir, "export fit.json --format px4 --drop-unsupported -o out.params");
  ASSERT_EQ(dropped.exit_code, 0) << dropped.err;
  EXPECT_NE(dropped.out.find("dropped dT: the instability on d.csv rises from"), std::string::npos) << dropped.out;
  // What the cubic costs is put down to the term left out, not to a range the record covers whole.
  EXPECT_NE(dropped.out.find("the terms it leaves out (dT) carry it"), std::string::npos) << dropped.out;
  EXPECT_EQ(dropped.out.find("outside the fitted range"), std::string::npos) << dropped.out;
  // The cubic left is the fit's own coefficients of T and T^2, not refitted.
  const Fitted fit = read_fit(nlohmann::json::parse(slurp(dir / "fit.json")));
  const auto p = read_qgc(slurp(dir / "out.params"));
  const double t = fit.tmin + 10.0;
  EXPECT_NEAR(px4_offset(p, 0, static_cast<float>(t)), fit.bias(t) * kDphToRadS, 1e-6 * std::abs(fit.bias(t) * kDphToRadS));
  // The cycle's bias follows dT: without it what is left, like a cubic fitted
  // alone, takes little off the instability, and export says so on stderr
  // (not in the file); the whole model in C does not draw the warning.
  EXPECT_NE(dropped.err.find("gyrotherm: warning: gyro_dph: the exported model takes the instability"),
            std::string::npos) << dropped.err;
  ASSERT_EQ(run_cli(dir, "fit d.csv --model 'T + T^2 + T^3' -o poly.json").exit_code, 0);
  // What dropping leaves is set beside the best the firmware can express: the cubic refitted on the same data.
  const double cubic = nlohmann::json::parse(slurp(dir / "poly.json"))["instability_after_dph"];
  EXPECT_NE(dropped.out.find(fmt::format("B = b0 + T + T^2 + T^3 refitted on the same data, leaves {:.6g} °/h", cubic)),
            std::string::npos) << dropped.out;
  const auto poly = run_cli(dir, "export poly.json --format ardupilot -o poly.param");
  ASSERT_EQ(poly.exit_code, 0) << poly.err;
  EXPECT_NE(poly.err.find("it compensates little"), std::string::npos) << poly.err;
  EXPECT_EQ(poly.out.find("compensates little"), std::string::npos) << poly.out;
  EXPECT_EQ(slurp(dir / "poly.param").find("compensates little"), std::string::npos);
  const auto whole = run_cli(dir, "export fit.json --format c -o whole.h");
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.err.find("warning"), std::string::npos) << whole.err;
}

TEST(CliExport, BadInputExitsTwoAndWritesNothing) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  ASSERT_EQ(run_cli(dir, "fit d.csv --model 'T + T^2' -o fit.json").exit_code, 0);
  expect_refused(dir, "export fit.json --format betaflight -o out.txt", "expected c, px4 or ardupilot");
  // Corrupt, and from a version that did not save the temperature range.
  gyrotherm::testing::write_text(dir / "corrupt.json", "{\"engine\": \"ols\", \"model\": ");
  expect_refused(dir, "export corrupt.json --format px4 -o out.txt", "corrupt.json: not a fit file: not JSON");
  nlohmann::json old = nlohmann::json::parse(slurp(dir / "fit.json"));
  old["data"].erase("temp_range_c");
  gyrotherm::testing::write_text(dir / "old.json", old.dump());
  expect_refused(dir, "export old.json --format ardupilot -o out.txt", "no data.temp_range_c");
  // record.reasons written by hand: not an object, or a reason with no name.
  nlohmann::json bad = nlohmann::json::parse(slurp(dir / "fit.json"));
  bad["record"]["reasons"] = nlohmann::json::array();
  gyrotherm::testing::write_text(dir / "bad.json", bad.dump());
  expect_refused(dir, "export bad.json --format px4 -o out.txt", "bad.json: record.reasons: expected {term: [reason, ...]}");
  bad["record"]["reasons"] = {{"T", {"cold"}}};
  gyrotherm::testing::write_text(dir / "bad.json", bad.dump());
  expect_refused(dir, "export bad.json --format px4 -o out.txt",
                 "bad.json: record.reasons.T: expected a list of narrow_range, few_levels, gap, time_locked");
  // --channel narrows a C export; a firmware file holds every axis, so it
  // would narrow only what is checked.
  for (const char* format : {"px4", "ardupilot"})
    expect_refused(dir, std::string("export fit.json --format ") + format + " --channel gyro_dph -o out.txt",
                   "a " + std::string(format) + " file holds every axis (choose and order them with --axes");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.txt"));
}

// A fit on two temperature plateaus (13 and 47.5 °C, two sessions joined):
// the parameters would claim the curve between them, where nothing was
// measured. export refuses, naming the caution, and writes nothing; with
// --accept-caution it writes the file with the caution at its top, on stderr
// and in --json.
TEST(CliExport, AFitOnTwoPlateausIsRefusedUnlessTheCautionIsAccepted) {
  ScratchDir dir;
  std::string csv = "time_s,temp_c,gyro_dph\n";
  for (int k = 0; k < 4 * 3600; ++k) {
    const double temp = k < 2 * 3600 ? 13.0 : 47.5;
    const double noise = 0.01 * std::sin(0.37 * k) + 0.007 * std::cos(1.9 * k);
    const double t = temp + 0.4 * std::sin(2.0 * M_PI * k / 1800.0);  // each session wanders a little
    csv += fmt::format("{},{:.3f},{:.6f}\n", k, t, 2.0 + 0.05 * t + noise);
  }
  gyrotherm::testing::write_text(dir / "plateaus.csv", csv);
  const auto fitted = run_cli(dir, "fit plateaus.csv --model 'T + T^2' -o fit.json");
  ASSERT_EQ(fitted.exit_code, 0) << fitted.err;
  const nlohmann::json fit = nlohmann::json::parse(slurp(dir / "fit.json"));
  EXPECT_EQ(fit["record"]["reasons"]["T^2"], nlohmann::json({"few_levels", "gap"})) << fit["record"].dump();
  for (const std::string format : {"px4", "ardupilot", "c"}) {
    const auto refused = run_cli(dir, "export fit.json --format " + format + " -o out.txt");
    EXPECT_EQ(refused.exit_code, 2) << format;
    EXPECT_NE(refused.err.find("cannot support these terms"), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("T^2: it rests on 2 temperature levels"), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("no data between 13.4 and 47.1 °C"), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("--accept-caution"), std::string::npos) << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.txt"));
    const auto accepted = run_cli(dir, "export fit.json --format " + format + " --accept-caution --json -o out.txt");
    ASSERT_EQ(accepted.exit_code, 0) << accepted.err;
    const std::string text = slurp(dir / "out.txt");
    const std::string comment = format == "c" ? "//" : "#";
    EXPECT_EQ(text.rfind(comment + " CAUTION (exported with --accept-caution)", 0), 0u) << text.substr(0, 200);
    EXPECT_NE(text.find(comment + "   gyro_dph: T^2: it rests on 2 temperature levels"), std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(accepted.out);
    bool warned = false;
    for (const auto& w : j["warnings"]) warned = warned || w.get<std::string>().rfind("caution: gyro_dph: T^2:", 0) == 0;
    EXPECT_TRUE(warned) << j["warnings"].dump();
    std::filesystem::remove(dir / "out.txt");
  }
}

// A fit on temperatures in kelvin read as °C, exported with --accept-caution
// and its own log as --data: the caution is said once (the fit's, by
// channel), not again for the log read a second time.
TEST(CliExport, AUnitCautionTheFitRecordedIsSaidOnceWithItsData) {
  ScratchDir dir;
  std::string csv = "time_s,temp_c,gyro_dph\n";
  for (int k = 0; k < 6 * 3600; ++k) {
    const double temp = 293.15 + 20.0 * std::sin(2.0 * M_PI * k / (6 * 3600.0));
    csv += fmt::format("{},{:.3f},{:.6f}\n", k, temp, 2.0 + 0.05 * (temp - 273.15) + 0.01 * std::sin(0.37 * k));
  }
  gyrotherm::testing::write_text(dir / "kelvin.csv", csv);
  ASSERT_EQ(run_cli(dir, "fit kelvin.csv --model T -o fit.json").exit_code, 0);
  const auto exported =
      run_cli(dir, "export fit.json --format px4 --data kelvin.csv --accept-caution --json -o out.params");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count(exported.err, "look like kelvin"), 1u) << exported.err;
  EXPECT_EQ(count(nlohmann::json::parse(exported.out).dump(), "look like kelvin"), 1u) << exported.out;
}

}  // namespace
}  // namespace gyrotherm::studies
