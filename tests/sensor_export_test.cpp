// The other sensors' firmware exports (studies/export/px4.cpp, ardupilot.cpp
// with fit/data/sensor_kind.h): an accelerometer's, a barometer's and a
// magnetometer's fit become PX4's TC_A, TC_B (a quintic, one channel) and
// TC_M, and an accelerometer's ArduPilot's INS_TCAL1_ACC*; each applied by
// its firmware's rule (tests/parameter_files.h, from the firmware sources)
// gives the fitted model's change from TREF (PX4: X0 is 0, the offset
// calibration's) or from the calibration temperature (ArduPilot); the
// outcome export predicts is in the sensor's unit; and each firmware that
// has no such compensation refuses it.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "fit/data/measurement.h"
#include "parameter_files.h"

namespace gyrotherm::studies {
namespace {

using testing::CliResult, testing::expect_refused, testing::run_cli, testing::run_shell, testing::ScratchDir;

// A 1 Hz, 3 h ramp 5 → 45 °C: column `column` holds `at_zero` + `slope`·T +
// `curve`·T² + a little noise, three times over for three axes when `axes`
// (the second axis 2·slope, the third −slope, less `down`: an
// accelerometer's gravity on z, which its three axes' magnitude must show).
void write_sensor_log(const ScratchDir& dir, const std::string& file, const std::string& column, double at_zero,
                      double slope, double curve, bool axes, double down = 0.0) {
  const std::string header = axes ? "time_s,temp_c," + column + "_x," + column + "_y," + column + "_z"
                                  : "time_s,temp_c," + column;
  const std::string values =
      axes ? "printf \"%d,%.6f,%.9g,%.9g,%.9g\\n\", k, t, b + s * t + c * t * t + n * u, b + 2 * s * t + n * u, "
             "-b - s * t + n * u - g"
           : "printf \"%d,%.6f,%.9g\\n\", k, t, b + s * t + c * t * t + n * u";
  const CliResult r = run_shell(
      dir, "awk -v g=" + std::to_string(down) + " -v b=" + std::to_string(at_zero) + " -v s=" + std::to_string(slope) + " -v c=" +
               std::to_string(curve) + " -v n=" + std::to_string(1e-3 * std::abs(slope) * 40.0) +
               " 'BEGIN { srand(3); print \"" + header +
               "\"; for (k = 0; k < 10800; k++) { t = 5 + 40 * k / 10800; u = rand() + rand() - 1; " + values +
               " } }' | tee " + file);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

// The fit's polynomial B(T) and its range, from its JSON.
struct FittedPolynomial {
  double c[6] = {0, 0, 0, 0, 0, 0};
  double tmin = 0, tmax = 0;
  double at(double t) const { return c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5])))); }
};
FittedPolynomial polynomial_in(const nlohmann::json& j) {
  FittedPolynomial f;
  f.c[0] = j["coefficients"]["1"];
  for (int k = 1; k <= 5; ++k)
    if (const std::string name = k == 1 ? "T" : "T^" + std::to_string(k); j["coefficients"].contains(name))
      f.c[k] = j["coefficients"][name];
  f.tmin = j["data"]["temp_range_c"][0];
  f.tmax = j["data"]["temp_range_c"][1];
  return f;
}

nlohmann::json channel_json(const nlohmann::json& j, std::size_t i) { return j.contains("channels") ? j["channels"][i] : j; }

// PX4 gives B(clamp(T)) − B(TREF) in the sensor's unit for every axis, and
// nothing of the constant (X0 = 0).
void expect_px4_gives_the_change(const std::map<std::string, float>& p, const std::string& stem, int order,
                                 const std::vector<std::string>& suffixes, const std::vector<FittedPolynomial>& fits) {
  const float tref = p.at(stem + "_TREF");
  for (std::size_t a = 0; a < suffixes.size(); ++a) {
    EXPECT_EQ(p.at(stem + "_X0" + suffixes[a]), 0.0f) << suffixes[a];
    const FittedPolynomial& f = fits[a];
    EXPECT_FLOAT_EQ(p.at(stem + "_TMIN"), static_cast<float>(f.tmin));
    for (int i = 0; i <= 100; ++i) {
      const double t = f.tmin - 10.0 + (f.tmax - f.tmin + 20.0) * i / 100.0;
      const double change = f.at(std::clamp(t, f.tmin, f.tmax)) - f.at(tref);
      const double scale = std::abs(f.at(f.tmax) - f.at(f.tmin)) + std::abs(f.at(tref));
      EXPECT_NEAR(testing::px4_offset_of(p, stem, suffixes[a], order, static_cast<float>(t)), change, 1e-6 * scale)
          << stem << suffixes[a] << " T = " << t;
    }
  }
}

TEST(SensorExport, AnAccelerometersFitBecomesPX4sTCAAndArduPilotsACC) {
  ScratchDir dir;
  write_sensor_log(dir, "a.csv", "accel", 0.3, 0.002, -1.5e-5, true, 9.80665);
  const CliResult fitted = run_cli(dir, "fit a.csv --sensor accel --gyro-col accel_x,accel_y,accel_z --model 'T + T^2' "
                                        "-o fit.json");
  ASSERT_EQ(fitted.exit_code, 0) << fitted.err;
  const nlohmann::json j = nlohmann::json::parse(testing::slurp(dir / "fit.json"));
  std::vector<FittedPolynomial> fits;
  for (std::size_t i = 0; i < 3; ++i) fits.push_back(polynomial_in(channel_json(j, i)));
  EXPECT_NEAR(fits[0].c[1], 0.002, 1e-4);  // the truth, m/s² per °C

  // The C compensator is a gyro's: refused at once, not after asking which of the three channels.
  expect_refused(dir, "export fit.json --format c -o a.h", "the C compensator is a gyro's");
  const CliResult px4 = run_cli(dir, "export fit.json --format px4 --device-id 1311004 --json -o a.params");
  ASSERT_EQ(px4.exit_code, 0) << px4.err;
  const std::string text = testing::slurp(dir / "a.params");
  const auto p = testing::read_qgc(text);
  EXPECT_EQ(p.at("TC_A_ENABLE"), 1.0f);
  EXPECT_EQ(p.at("TC_A0_ID"), 1311004.0f);
  EXPECT_EQ(p.count("TC_G_ENABLE"), 0u);
  EXPECT_NE(text.find("accelerometer thermal compensation from fit.json"), std::string::npos) << text;
  EXPECT_NE(text.find("(m/s², T in °C)"), std::string::npos) << text;
  EXPECT_NE(text.find("X0 is 0"), std::string::npos) << text;
  expect_px4_gives_the_change(p, "TC_A0", 3, {"_0", "_1", "_2"}, fits);
  // The predicted outcome, in m/s²: the record less what PX4 subtracts by its
  // own rule (once a second, on a 1 °C move), as the test applies it.
  const nlohmann::json out = nlohmann::json::parse(px4.out);
  fit::ColumnMap columns;
  columns.gyro = "accel_x";
  columns.units.sensor = "accel";
  const fit::Measurement m = fit::read_measurement_csv(dir / "a.csv", columns);
  const double firmware = testing::instability(
      m, testing::px4_as_applied(m, [&](float t) { return testing::px4_offset_of(p, "TC_A0", "_0", 3, t); }, 1.0));
  const nlohmann::json& axis = out["firmware_outcome"]["axes"][0];
  EXPECT_NEAR(axis["firmware_dph"].get<double>(), firmware, 1e-9 * firmware);
  EXPECT_LT(axis["firmware_dph"].get<double>(), 0.2 * axis["instability_before_dph"].get<double>());
  bool said_unit = false;
  for (const auto& line : out["lines"]) said_unit = said_unit || line.get<std::string>().find("m/s²") != std::string::npos;
  EXPECT_TRUE(said_unit) << out["lines"].dump();
  EXPECT_EQ(px4.out.find("°/h"), std::string::npos) << px4.out;
  EXPECT_EQ(px4.err.find("°/h"), std::string::npos) << px4.err;

  // ArduPilot: the change from the calibration temperature, ×1e6 in m/s².
  const CliResult ap = run_cli(dir, "export fit.json --format ardupilot -o a.param");
  ASSERT_EQ(ap.exit_code, 0) << ap.err;
  const std::string ap_text = testing::slurp(dir / "a.param");
  const auto a = testing::read_ap(ap_text);
  EXPECT_EQ(a.count("INS_TCAL1_GYR1_X"), 0u);
  EXPECT_NE(ap_text.find("INS_ACC{n}_CALTEMP"), std::string::npos);
  EXPECT_NE(ap_text.find("TMIN and TMAX are the gyro's too"), std::string::npos);
  for (const double cal : {fits[0].tmin + 2.0, 25.0})
    for (const double t : {fits[0].tmin, 20.0, 30.0, fits[0].tmax, fits[0].tmax + 5.0}) {
      const double truth = fits[0].at(std::clamp(t, fits[0].tmin, fits[0].tmax)) - fits[0].at(cal);
      EXPECT_NEAR(testing::ardupilot_subtracted(a, 'X', static_cast<float>(t), static_cast<float>(cal), "ACC"), truth,
                  1e-6 * 0.1)
          << "T = " << t << ", CALTEMP = " << cal;
    }
}

TEST(SensorExport, ABarometersFitBecomesPX4sQuinticTCB) {
  ScratchDir dir;
  write_sensor_log(dir, "b.csv", "baro_pa", 101325.0, 3.0, 0.02, false);
  // A quartic: PX4's barometer takes up to T^5, its gyro only T^3.
  const CliResult fitted = run_cli(dir, "fit b.csv --sensor baro --model 'T + T^2 + T^3 + T^4' -o fit.json");
  ASSERT_EQ(fitted.exit_code, 0) << fitted.err;
  const FittedPolynomial f = polynomial_in(nlohmann::json::parse(testing::slurp(dir / "fit.json")));
  const CliResult px4 = run_cli(dir, "export fit.json --format px4 -o b.params");
  ASSERT_EQ(px4.exit_code, 0) << px4.err;
  const std::string text = testing::slurp(dir / "b.params");
  const auto p = testing::read_qgc(text);
  EXPECT_EQ(p.at("TC_B_ENABLE"), 1.0f);
  EXPECT_EQ(p.count("TC_B0_X0_0"), 0u);  // one channel: no axis suffix
  EXPECT_EQ(p.at("TC_B0_X5"), 0.0f);     // the model has no T^5
  EXPECT_NE(p.at("TC_B0_X4"), 0.0f);
  EXPECT_NE(text.find("calc_thermal_offsets_1D"), std::string::npos) << text;
  EXPECT_NE(px4.out.find("wrote b.params: PX4 barometer thermal compensation (baro_pa)"), std::string::npos) << px4.out;
  EXPECT_NE(px4.out.find("exported quintic"), std::string::npos) << px4.out;
  expect_px4_gives_the_change(p, "TC_B0", 5, {""}, {f});
  // ArduPilot has no barometer polynomial; the C compensator is a gyro's; a quartic is not a gyro's cubic.
  expect_refused(dir, "export fit.json --format ardupilot -o b.param",
                 "ArduPilot has no temperature calibration of a barometer");
  expect_refused(dir, "export fit.json --format c -o b.h", "the C compensator is a gyro's");
  EXPECT_FALSE(std::filesystem::exists(dir / "b.param") || std::filesystem::exists(dir / "b.h"));
  // A term PX4 cannot express, dropped: the best polynomial it can is refitted up to the quintic, and the
  // command to fit it names the sensor and its column. (Temperature up, then down, so that t is not T.)
  ASSERT_EQ(run_shell(dir, "awk -F, 'NR == 1 || NR % 2 == 0 { print } NR > 1 && NR % 2 == 1 { n[++m] = $0 } "
                           "END { for (i = m; i > 0; i--) { split(n[i], f, \",\"); print 10800 + m - i \",\" f[2] "
                           "\",\" f[3] } }' b.csv | tee b2.csv")
                .exit_code,
            0);
  ASSERT_EQ(run_cli(dir, "fit b2.csv --sensor baro --model 'T + T^2 + t' -o t_fit.json").exit_code, 0);
  const CliResult dropped = run_cli(dir, "export t_fit.json --format px4 --drop-unsupported -o t.params");
  ASSERT_EQ(dropped.exit_code, 0) << dropped.err;
  EXPECT_NE(dropped.out.find("B = b0 + T + T^2 + T^3 + T^4"), std::string::npos) << dropped.out;
  EXPECT_NE(dropped.out.find("gyrotherm fit b2.csv --sensor baro --gyro-col 'baro_pa' --model"), std::string::npos)
      << dropped.out;
  EXPECT_EQ(dropped.out.find("--format c"), std::string::npos) << dropped.out;
  // TC_B holds one channel: a fit of two pressure columns is refused, and nothing is written.
  ASSERT_EQ(run_shell(dir, "awk -F, 'NR == 1 { print \"time_s,temp_c,p1_pa,p2_pa\"; next } "
                           "{ print $1 \",\" $2 \",\" $3 \",\" $3 + 5 }' b.csv | tee two.csv")
                .exit_code,
            0);
  ASSERT_EQ(run_cli(dir, "fit two.csv --sensor baro --gyro-col p1_pa,p2_pa --model T -o two.json").exit_code, 0);
  expect_refused(dir, "export two.json --format px4 -o two.params",
                 "a barometer's thermal compensation holds one channel; give a fit of one (or --axes NAME,-,-)");
  EXPECT_FALSE(std::filesystem::exists(dir / "two.params"));
  EXPECT_EQ(run_cli(dir, "export two.json --format px4 --axes p1_pa,-,- -o one.params").exit_code, 0);
}

TEST(SensorExport, AMagnetometersFitBecomesPX4sTCMAndAGyrosIsAsItWas) {
  ScratchDir dir;
  write_sensor_log(dir, "m.csv", "mag_gauss", 0.2, 5e-4, 0.0, true);
  ASSERT_EQ(run_cli(dir, "fit m.csv --sensor mag --gyro-col mag_gauss_x,mag_gauss_y,mag_gauss_z --model T -o fit.json")
                .exit_code,
            0);
  const nlohmann::json j = nlohmann::json::parse(testing::slurp(dir / "fit.json"));
  const CliResult px4 = run_cli(dir, "export fit.json --format px4 --instance 1 -o m.params");
  ASSERT_EQ(px4.exit_code, 0) << px4.err;
  const auto p = testing::read_qgc(testing::slurp(dir / "m.params"));
  EXPECT_EQ(p.at("TC_M_ENABLE"), 1.0f);
  EXPECT_NE(px4.out.find("set TC_M1_ID to your magnetometer's device id (CAL_MAG1_ID)"), std::string::npos) << px4.out;
  expect_px4_gives_the_change(p, "TC_M1", 3, {"_0", "_1", "_2"},
                              {polynomial_in(channel_json(j, 0)), polynomial_in(channel_json(j, 1)),
                               polynomial_in(channel_json(j, 2))});
  // A fit file whose sensor was edited against its units is refused.
  ASSERT_EQ(run_shell(dir, "sed -i '0,/\"sensor\": \"mag\"/s//\"sensor\": \"gyro\"/' fit.json").exit_code, 0);
  expect_refused(dir, "export fit.json --format px4 -o x.params", "but pipeline.columns.units.sensor is mag");
}

}  // namespace
}  // namespace gyrotherm::studies
