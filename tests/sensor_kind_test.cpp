// The sensor kinds (fit/data/sensor_kind.h): the registry, their units and
// how column names state them, and `fit --sensor` on an accelerometer's and a
// barometer's CSV channel, with every refusal.

#include "fit/data/sensor_kind.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "fit/data/header_units.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using testing::CliResult;
using testing::expect_refused;
using testing::run_cli;
using testing::run_shell;
using testing::ScratchDir;

TEST(SensorKind, EachKindIsNamedOnceWithABaseUnitItsDefaultColumnStates) {
  std::set<std::string_view> names;
  for (const SensorKind& k : sensor_kinds()) {
    EXPECT_TRUE(names.insert(k.name).second) << k.name;
    const std::string_view base = base_unit(k.quantity);
    ASSERT_FALSE(base.empty()) << k.name;
    const HeaderUnit stated = unit_in_header(k.quantity, k.column);
    ASSERT_NE(stated.unit, nullptr) << k.column;
    EXPECT_EQ(stated.unit->name, base) << k.column;
    EXPECT_TRUE(names_sensor(k.column, k)) << k.column;
  }
  EXPECT_EQ(&sensor_kind(""), &sensor_kind("gyro"));
  EXPECT_EQ(&sensor_kind("accel"), &sensor_kind("accel"));
  EXPECT_EQ(sensor_kind_names(), "gyro, accel, baro or mag");
  try {
    sensor_kind("compass");
    ADD_FAILURE() << "--sensor compass was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--sensor 'compass': must be gyro, accel, baro or mag");
  }
}

TEST(SensorKind, NoiseFactorsTurnTheAmplitudesIntoTheNamedUnits) {
  // q_w in base²·s: √q_w is base·√s, and √s = √h/60. A gyro's °/h·√s is
  // °/√h ÷ 60; an accelerometer's m/s²·√s is m/s/√s = 60 m/s/√h; a
  // barometer's is given in Pa·√s as it is. q_r in base²/s: √q_r base/√s =
  // 60 base/√h for each.
  const double per_sqrt_h = std::sqrt(3600.0);
  EXPECT_DOUBLE_EQ(sensor_kind("gyro").noise[0].factor, 1.0 / per_sqrt_h);
  EXPECT_EQ(sensor_kind("gyro").noise[0].name, "arw");
  EXPECT_DOUBLE_EQ(sensor_kind("accel").noise[0].factor, per_sqrt_h);
  EXPECT_EQ(sensor_kind("accel").noise[0].name, "vrw");
  EXPECT_EQ(sensor_kind("accel").noise[0].unit, "m/s/sqrt(h)");
  EXPECT_DOUBLE_EQ(sensor_kind("baro").noise[0].factor, 1.0);
  for (const SensorKind& k : sensor_kinds()) EXPECT_DOUBLE_EQ(k.noise[3].factor, per_sqrt_h) << k.name;
}

TEST(SensorKind, ColumnNamesStateAccelerometerAndPressureUnits) {
  const auto stated = [](Quantity q, const char* column) {
    const Unit* u = unit_in_header(q, column).unit;
    return u == nullptr ? std::string("none") : std::string(u->name);
  };
  EXPECT_EQ(stated(Quantity::accel, "accel_x_mps2"), "mps2");
  EXPECT_EQ(stated(Quantity::accel, "ax [m/s^2]"), "mps2");
  EXPECT_EQ(stated(Quantity::accel, "ax [m/s²]"), "mps2");
  EXPECT_EQ(stated(Quantity::accel, "acc (g)"), "g");
  EXPECT_EQ(stated(Quantity::accel, "acc_z_mg"), "mg");
  EXPECT_EQ(stated(Quantity::accel, "AccX"), "none");
  EXPECT_EQ(stated(Quantity::accel, "imu.acc.x"), "none");
  EXPECT_EQ(stated(Quantity::pressure, "press (hPa)"), "hPa");
  EXPECT_EQ(stated(Quantity::pressure, "baro_pa"), "Pa");
  EXPECT_EQ(stated(Quantity::pressure, "pressure [mbar]"), "mbar");
  EXPECT_EQ(stated(Quantity::gyro, "press (hPa)"), "none");
  EXPECT_EQ(stated(Quantity::magnetic, "mag1x [T]"), "T");
  EXPECT_EQ(stated(Quantity::magnetic, "field_uT"), "uT");
  EXPECT_EQ(stated(Quantity::magnetic, "mag_x_mG"), "mgauss");
  EXPECT_EQ(stated(Quantity::magnetic, "mag (G)"), "gauss");
  EXPECT_DOUBLE_EQ(find_unit(Quantity::magnetic, "T", "--gyro-unit").factor, 1e4);  // gauss
  EXPECT_DOUBLE_EQ(find_unit(Quantity::magnetic, "uT", "--gyro-unit").factor, 1e-2);
  EXPECT_DOUBLE_EQ(find_unit(Quantity::accel, "g", "--gyro-unit").factor, 9.80665);
  EXPECT_DOUBLE_EQ(find_unit(Quantity::accel, "mg", "--gyro-unit").factor, 9.80665e-3);
  EXPECT_DOUBLE_EQ(find_unit(Quantity::pressure, "hPa", "--gyro-unit").factor, 100.0);
  EXPECT_DOUBLE_EQ(find_unit(Quantity::pressure, "mbar", "--gyro-unit").factor, 100.0);
  EXPECT_DOUBLE_EQ(find_unit(Quantity::pressure, "kPa", "--gyro-unit").factor, 1000.0);
}

TEST(SensorKind, LoggersColumnNamesSayTheirSensor) {
  EXPECT_TRUE(names_sensor("imu.acc.x", sensor_kind("accel")));
  EXPECT_TRUE(names_sensor("AccX", sensor_kind("accel")));
  EXPECT_TRUE(names_sensor("accel_x_mps2", sensor_kind("accel")));
  EXPECT_FALSE(names_sensor("accel_temp", sensor_kind("accel")));  // its temperature
  EXPECT_FALSE(names_sensor("GyrX", sensor_kind("accel")));
  EXPECT_TRUE(names_sensor("GyrX", sensor_kind("gyro")));
  EXPECT_TRUE(names_sensor("BARO.Press", sensor_kind("baro")));
  EXPECT_FALSE(names_sensor("time_s", sensor_kind("baro")));
  EXPECT_TRUE(names_sensor("mag1x [T]", sensor_kind("mag")));
}

// A 1 Hz, 2 h ramp 0 → 40 °C: an accelerometer axis of 0.3 m/s² + 0.002
// m/s²/°C · T with 0.01 m/s² of white noise, in column `column`, its numbers
// divided by `divide` (the unit's factor).
void write_accel_log(const ScratchDir& dir, const std::string& file, const std::string& column, double divide) {
  const CliResult r = run_shell(
      dir, "awk -v d=" + std::to_string(divide) + " 'BEGIN { srand(7); print \"time_s,temp_c," + column +
               "\"; for (k = 0; k < 7200; k++) { t = 40 * k / 7200; u = rand() + rand() + rand() - 1.5; "
               "printf \"%d,%.6f,%.9g\\n\", k, t, (0.3 + 0.002 * t + 0.02 * u) / d } }' | tee " + file);
  ASSERT_EQ(r.exit_code, 0) << r.err;
}

nlohmann::json fit_json(const ScratchDir& dir, const std::string& args) {
  const CliResult r = run_cli(dir, "fit " + args + " --json");
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return r.exit_code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}

// The same log written in the base unit (column `base`) and in another
// (`other`, its numbers divided by `factor`), each fitted with `args`: the
// two fits, whose coefficients must agree (the numbers are written to 9 digits).
std::pair<nlohmann::json, nlohmann::json> fit_both(const ScratchDir& dir, const std::string& base,
                                                   const std::string& other, double factor, const std::string& args) {
  write_accel_log(dir, "base.csv", base, 1.0);
  write_accel_log(dir, "other.csv", other, factor);
  const nlohmann::json a = fit_json(dir, "base.csv --gyro-col '" + base + "' --model T " + args);
  const nlohmann::json b = fit_json(dir, "other.csv --gyro-col '" + other + "' --model T " + args);
  EXPECT_TRUE(a.contains("coefficients") && b.contains("coefficients"));
  if (a.contains("coefficients") && b.contains("coefficients")) {
    const double slope = a["coefficients"]["T"].get<double>();
    EXPECT_NEAR(slope, 0.002, 2e-4);  // the truth, in the base unit per °C
    EXPECT_NEAR(b["coefficients"]["T"].get<double>(), slope, 1e-6 * std::abs(slope));
    EXPECT_NEAR(b["coefficients"]["1"].get<double>(), a["coefficients"]["1"].get<double>(), 1e-6);
  }
  return {a, b};
}

TEST(CliSensor, AnAccelerometerIsFittedInItsUnitsWhateverTheLoggerWrote) {
  ScratchDir dir;
  const auto [si, g] = fit_both(dir, "imu.acc.x", "ax [g]", 9.80665, "--sensor accel");
  ASSERT_TRUE(si.contains("noise_model"));
  EXPECT_EQ(si["sensor"], "accel");
  EXPECT_EQ(si["unit"], "m/s²");
  EXPECT_EQ(si["pipeline"]["columns"]["units"]["sensor"], "accel");
  EXPECT_EQ(g["pipeline"]["columns"]["units"]["gyro"], "g");
  // The noise by an accelerometer's names and units.
  const nlohmann::json& components = si["noise_model"]["components"];
  ASSERT_TRUE(components.contains("vrw")) << components.dump();
  EXPECT_EQ(components["vrw"]["unit"], "m/s/sqrt(h)");
  EXPECT_FALSE(components.contains("arw"));

  const CliResult text = run_cli(dir, "fit base.csv --sensor accel --gyro-col imu.acc.x --model T");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("accel mps2 (default)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("m/s² per °C"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("vrw "), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("°/h"), std::string::npos) << text.out;
}

TEST(CliSensor, ABarometerInHectopascalsIsFittedInPascals) {
  ScratchDir dir;
  const auto [pa, hpa] = fit_both(dir, "baro_pa", "press (hPa)", 100.0, "--sensor baro");
  EXPECT_EQ(pa["unit"], "Pa");
  EXPECT_EQ(hpa["pipeline"]["columns"]["units"]["gyro"], "hPa");
}

TEST(CliSensor, AGyroFitIsAsItWas) {
  ScratchDir dir;
  testing::write_ramp_log(dir / "g.csv", "gyro_dph", {0.5}, 2.0, 0.0, 40.0, 3);
  const nlohmann::json j = fit_json(dir, "g.csv --model T");
  EXPECT_FALSE(j.contains("sensor"));
  EXPECT_FALSE(j.contains("unit"));
  EXPECT_FALSE(j["pipeline"]["columns"]["units"].contains("sensor"));
  EXPECT_TRUE(j["noise_model"]["components"].contains("arw"));
}

TEST(CliSensor, EveryMismatchOfSensorColumnAndUnitIsRefused) {
  ScratchDir dir;
  write_accel_log(dir, "a.csv", "accel_x_mps2", 1.0);
  testing::write_ramp_log(dir / "g.csv", "rate_dph", {0.5}, 2.0, 0.0, 40.0, 3);
  expect_refused(dir, "fit a.csv --sensor compass", "--sensor 'compass': must be gyro, accel, baro or mag");
  // A unit that is not the sensor's.
  expect_refused(dir, "fit a.csv --sensor accel --gyro-col accel_x_mps2 --gyro-unit dph",
                 "--gyro-unit dph: degrees per hour, a unit of the gyro, but the column is read as the "
                 "accelerometer's (--sensor accel); give --sensor gyro, or one of mps2, g, mg or ug");
  // A column whose name states another sensor's unit: never read in this one's.
  expect_refused(dir, "fit a.csv --gyro-col accel_x_mps2",
                 "column 'accel_x_mps2' states mps2 (metres per second squared), a unit of the accelerometer, "
                 "but it is read as the gyro's (--sensor gyro): give --sensor accel");
  expect_refused(dir, "fit g.csv --sensor accel --gyro-col rate_dph", "a unit of the gyro");
  // A column named as another kind's, by its words: refused unless --gyro-unit states it.
  write_accel_log(dir, "x.csv", "AccX", 1.0);
  expect_refused(dir, "fit x.csv --gyro-col AccX",
                 "column 'AccX' is named as the accelerometer's, but it is read as the gyro's (--sensor gyro)");
  EXPECT_EQ(run_cli(dir, "fit x.csv --gyro-col AccX --gyro-unit dph --model T").exit_code, 0);
  // A unit of another kind.
  expect_refused(dir, "fit a.csv --gyro-col accel_x_mps2 --gyro-unit mps2",
                 "--gyro-unit mps2: metres per second squared, a unit of the accelerometer, but the column is read "
                 "as the gyro's (--sensor gyro); give --sensor accel");
  // The default column absent: the error names the columns that look like the sensor's.
  expect_refused(dir, "fit a.csv",
                 "accel_x_mps2 may be the accelerometer's: to fit it, give --sensor accel --gyro-col 'accel_x_mps2'");
  // (With --sensor accel its one column is read by its role: tests/column_by_role_test.cpp.)
  // An accelerometer's fit file is not applied as a gyro's, nor its noise planned with.
  ASSERT_EQ(run_cli(dir, "fit a.csv --sensor accel --gyro-col accel_x_mps2 --model T -o a_fit.json").exit_code, 0);
  expect_refused(dir, "plan --noise a_fit.json --model T", "plan designs a gyro's test only, so far");
  expect_refused(dir, "report a.csv --fit a_fit.json -o r.html", "accel");
  expect_refused(dir, "report a.csv --fit a_fit.json -o r.html",
                 "pipeline.columns.units.sensor is accel (the accelerometer's fit): report takes a gyro's fit only");
  EXPECT_EQ(run_cli(dir, "report a.csv --fit a_fit.json -o r.html").err.find("fitting"), std::string::npos)
      << "refused before any work";
  expect_refused(dir, "compensate a.csv --fit a_fit.json --sensor gyro -o out.csv",
                 "--sensor gyro: a_fit.json is the accelerometer's fit (--sensor accel)");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
  // A fit file whose units were edited away still names its sensor at the top.
  ASSERT_EQ(run_cli(dir, "fit g.csv --gyro-col rate_dph --model T -o g_fit.json").exit_code, 0);
  ASSERT_EQ(run_shell(dir, "sed -i '1s/^{/{\"sensor\": \"accel\",/' g_fit.json").exit_code, 0);
  expect_refused(dir, "check g.csv --params g_fit.json",
                 "its \"sensor\" is \"accel\" but pipeline.columns.units.sensor is gyro");
  expect_refused(dir, "report g.csv --fit g_fit.json -o r.html",
                 "the fit of a sensor of kind \"accel\" (its \"sensor\"): report takes");
  expect_refused(dir, "compensate g.csv --fit g_fit.json -o out.csv",
                 "its \"sensor\" is \"accel\" but pipeline.columns.units.sensor is gyro");
  EXPECT_FALSE(std::filesystem::exists(dir / "out.csv"));
}

// compensate applies an accelerometer's fit in m/s², its columns named so.
TEST(CliSensor, AnAccelerometersFitIsAppliedInItsUnits) {
  ScratchDir dir;
  write_accel_log(dir, "a.csv", "ax [g]", 9.80665);
  ASSERT_EQ(run_cli(dir, "fit a.csv --sensor accel --gyro-col 'ax [g]' --model T -o fit.json").exit_code, 0);
  const CliResult r = run_cli(dir, "compensate a.csv --fit fit.json -o out.csv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sensor"], "accel");
  EXPECT_EQ(j["unit"], "m/s²");
  EXPECT_LT(j["instability_after_dph"].get<double>(), 0.1 * j["instability_before_dph"].get<double>());
  const std::string out = testing::slurp(dir / "out.csv");
  EXPECT_NE(out.find("time_s,temp_c,accel_mps2,model_mps2,compensated_mps2,outlier\n"), std::string::npos) << out.substr(0, 300);
  EXPECT_NE(out.find("m/s^2"), std::string::npos);
  // The compensated column: the raw in m/s² (0.3 + 0.002 T) less the model, flat about the constant.
  const CliResult last = run_shell(dir, "tail -1 out.csv");
  double t = 0, temp = 0, raw = 0, model = 0, compensated = 0;
  ASSERT_EQ(std::sscanf(last.out.c_str(), "%lf,%lf,%lf,%lf,%lf", &t, &temp, &raw, &model, &compensated), 5);
  EXPECT_NEAR(model, 0.3 + 0.002 * temp, 0.005);
  EXPECT_NEAR(raw, 0.3 + 0.002 * temp, 0.1);  // m/s², not g
  const CliResult text = run_cli(dir, "compensate a.csv --fit fit.json");
  EXPECT_NE(text.out.find(" m/s² ("), std::string::npos) << text.out;
  // Several channels: each named with its unit, the columns say m/s².
  ASSERT_EQ(run_shell(dir, "awk -F, 'NR == 1 { print \"time_s,temp_c,acc_x (g),acc_y (g)\"; next } "
                          "{ print $1 \",\" $2 \",\" $3 \",\" (-$3) }' a.csv | tee two.csv")
                .exit_code,
            0);
  ASSERT_EQ(run_cli(dir, "fit two.csv --sensor accel --gyro-col 'acc_x (g),acc_y (g)' --model T -o two.json").exit_code, 0);
  ASSERT_EQ(run_cli(dir, "compensate two.csv --fit two.json -o two_out.csv").exit_code, 0);
  EXPECT_NE(testing::slurp(dir / "two_out.csv").find("acc_x_mps2,acc_x_model_mps2,acc_x_compensated_mps2"),
            std::string::npos)
      << testing::slurp(dir / "two_out.csv").substr(0, 400);
}

// allan on an accelerometer's and a barometer's white noise: 0.01 m/s² at
// 1 s is a velocity random walk of 0.01·√3600 = 0.6 m/s/√h; 2 Pa at 1 s a
// white noise density of 2 Pa·√s. Named and united as each sensor's.
TEST(CliSensor, AllanReportsEachSensorsNoiseInItsUnits) {
  ScratchDir dir;
  const auto write_white = [&](const std::string& file, const std::string& column, double level, double sigma) {
    const CliResult r = run_shell(dir, "awk 'BEGIN { srand(11); print \"time_s,temp_c," + column +
                                           "\"; for (k = 0; k < 40000; k++) { u = -6; for (i = 0; i < 12; i++) "
                                           "u += rand(); printf \"%d,%.4f,%.9g\\n\", k, 20 + k / 2000, " +
                                           std::to_string(level) + " + " + std::to_string(sigma) + " * u } }' | tee " +
                                           file);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  };
  write_white("a.csv", "accel_mps2", 0.3, 0.01);
  write_white("b.csv", "baro_pa", 101325.0, 2.0);
  const CliResult a = run_cli(dir, "allan a.csv --sensor accel --json");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const nlohmann::json ja = nlohmann::json::parse(a.out);
  EXPECT_EQ(ja["sensor"], "accel");
  const nlohmann::json& ka = ja["series"][0]["coefficients"];
  ASSERT_TRUE(ka.contains("vrw") && ka.contains("accel_random_walk")) << ka.dump();
  EXPECT_FALSE(ka.contains("arw_dpsh"));
  EXPECT_NEAR(ka["vrw"]["value"].get<double>(), 0.6, 0.03);
  EXPECT_LE(ka["vrw"]["lo"].get<double>(), ka["vrw"]["value"].get<double>());
  const CliResult text = run_cli(dir, "allan a.csv --sensor accel");
  EXPECT_NE(text.out.find("velocity random walk"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("m/s/√h"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("adev (m/s²)"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("°/h"), std::string::npos) << text.out;
  // The noise type of each τ by the sensor's words, not a gyro's angle random walk.
  EXPECT_NE(text.out.find("velocity_random_walk"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("angle_random_walk"), std::string::npos) << text.out;
  const CliResult b = run_cli(dir, "allan b.csv --sensor baro --json");
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const nlohmann::json kb = nlohmann::json::parse(b.out)["series"][0]["coefficients"];
  ASSERT_TRUE(kb.contains("white_noise")) << kb.dump();
  EXPECT_NEAR(kb["white_noise"]["value"].get<double>(), 2.0, 0.1);
  // With a fit: the sensor is the fit's.
  ASSERT_EQ(run_cli(dir, "fit a.csv --sensor accel --model T -o fit.json").exit_code, 0);
  const CliResult with_fit = run_cli(dir, "allan a.csv --fit fit.json --json");
  ASSERT_EQ(with_fit.exit_code, 0) << with_fit.err;
  const nlohmann::json jf = nlohmann::json::parse(with_fit.out);
  EXPECT_EQ(jf["sensor"], "accel");
  ASSERT_EQ(jf["series"].size(), 2u);
  EXPECT_EQ(jf["series"][1]["name"], "compensated");
  EXPECT_NEAR(jf["series"][1]["coefficients"]["vrw"]["value"].get<double>(), 0.6, 0.03);
  expect_refused(dir, "allan a.csv --fit fit.json --sensor baro", "--sensor baro: fit.json is the accelerometer's fit");
}

// An accelerometer that moved: sample-to-sample changes no accelerometer's
// noise makes (0.5 m/s² at 1 s is a velocity random walk of 30 m/s/√h), as
// a flying vehicle's do; a still one (0.01 m/s², 0.6 m/s/√h) is not cautioned.
TEST(CliSensor, AnAccelerometerThatMovedIsCautioned) {
  ScratchDir dir;
  for (const auto& [file, sigma] : {std::pair{"still.csv", 0.01}, {"shaken.csv", 0.5}}) {
    const CliResult r = run_shell(dir, "awk 'BEGIN { srand(5); print \"time_s,temp_c,accel_mps2\"; for (k = 0; k < 7200; "
                                       "k++) { u = -6; for (i = 0; i < 12; i++) u += rand(); printf \"%d,%.4f,%.9g\\n\", "
                                       "k, 20 + k / 360, 0.3 + " + std::to_string(sigma) + " * u } }' | tee " + file);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const nlohmann::json still = fit_json(dir, "still.csv --sensor accel --model T");
  EXPECT_TRUE(still["data"]["cautions"].empty()) << still["data"]["cautions"].dump();
  const CliResult shaken = run_cli(dir, "fit shaken.csv --sensor accel --model T");
  ASSERT_EQ(shaken.exit_code, 0) << shaken.err;
  const std::size_t at = shaken.out.find("a velocity random walk of ");
  ASSERT_NE(at, std::string::npos) << shaken.out;
  EXPECT_NEAR(std::stod(shaken.out.substr(at + 26, 8)), 30.0, 2.0) << shaken.out;  // 0.5 · 60
  EXPECT_NE(shaken.out.find("it moved or vibrated"), std::string::npos) << shaken.out;
  // A real flight: PX4's quadrotor log, its accelerometer in the unit the format states.
  const std::string log = testing::source_path("../shared/data/real/px4_ulog/quadrotor_local.ulg");
  if (!std::filesystem::exists(log)) GTEST_SKIP() << "no real PX4 log at " << log;
  const CliResult flight = run_cli(dir, "fit " + log + " --sensor accel --gyro-col accel_z --avg 5 --model T");
  ASSERT_EQ(flight.exit_code, 0) << flight.err;
  EXPECT_NE(flight.out.find("the vehicle moved or vibrated"), std::string::npos) << flight.out;
}

// Numbers that look like another unit than they are read in get a caution:
// an atmosphere in hPa read as Pa, a field in µT read as gauss.
TEST(CliSensor, ReadingsOutsideTheSensorsRangeAreCautioned) {
  ScratchDir dir;
  const CliResult made = run_shell(dir,
                                   "awk 'BEGIN { srand(3); print \"time_s,temp_c,pressure,field\"; for (k = 0; k < 7200; "
                                   "k++) { t = 40 * k / 7200; print k \",\" t \",\" 1013 + 0.01 * t + 0.05 * rand() "
                                   "\",\" 45 + 0.001 * t + 0.01 * rand() } }' | tee p.csv");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const nlohmann::json hpa = fit_json(dir, "p.csv --sensor baro --gyro-col pressure --model T");
  ASSERT_TRUE(hpa.contains("data"));
  ASSERT_EQ(hpa["data"]["cautions"].size(), 1u) << hpa["data"]["cautions"].dump();
  EXPECT_NE(hpa["data"]["cautions"][0].get<std::string>().find("an atmosphere written in hPa or mbar read as Pa?"),
            std::string::npos);
  const nlohmann::json right = fit_json(dir, "p.csv --sensor baro --gyro-col pressure --gyro-unit hPa --model T");
  EXPECT_TRUE(right["data"]["cautions"].empty()) << right["data"]["cautions"].dump();
  const nlohmann::json ut = fit_json(dir, "p.csv --sensor mag --gyro-col field --model T");
  ASSERT_EQ(ut["data"]["cautions"].size(), 1u);
  EXPECT_NE(ut["data"]["cautions"][0].get<std::string>().find("milligauss, uT or nT read as gauss?"), std::string::npos);
  EXPECT_TRUE(fit_json(dir, "p.csv --sensor mag --gyro-col field --gyro-unit uT --model T")["data"]["cautions"].empty());
  // The numbers in a smaller unit than the one the user gave: said as such, not as "read as Pa".
  const nlohmann::json mpa = fit_json(dir, "p.csv --sensor baro --gyro-col pressure --gyro-unit mbar --model T");
  EXPECT_TRUE(mpa["data"]["cautions"].empty());
  const CliResult shell = run_shell(dir, "awk -F, 'NR == 1 { print; next } { $3 = $3 * 100; print }' OFS=, p.csv | tee pa.csv");
  ASSERT_EQ(shell.exit_code, 0);
  const nlohmann::json pa_as_hpa = fit_json(dir, "pa.csv --sensor baro --gyro-col pressure --gyro-unit hPa --model T");
  ASSERT_EQ(pa_as_hpa["data"]["cautions"].size(), 1u) << pa_as_hpa["data"]["cautions"].dump();
  EXPECT_NE(pa_as_hpa["data"]["cautions"][0].get<std::string>().find("numbers in a smaller unit than hPa?"),
            std::string::npos)
      << pa_as_hpa["data"]["cautions"][0];
}

// A real magnetometer (the PAN cubesat's, in a thermal-vacuum chamber, its
// field in tesla): read in gauss, where the Earth's field and a board's are
// well under 1 gauss. Skipped without the log (../shared/data/real/pan_tvac/).
TEST(CliSensor, ARealMagnetometerInTeslaIsFittedInGauss) {
  const std::filesystem::path log =
      std::filesystem::path(GYROTHERM_SOURCE_DIR) / ".." / "shared" / "data" / "real" / "pan_tvac" / "TVCtest3_7_20.csv";
  if (!std::filesystem::exists(log)) GTEST_SKIP() << "no " << log.string();
  ScratchDir dir;
  const std::string args = "'" + log.string() +
                           "' --sensor mag --gyro-col 'mag1x [T]' --time-col 'time (ms)' --temp-col temp "
                           "--temp-scale 0.00390625 --temp-offset -231 --model T";
  const nlohmann::json j = fit_json(dir, args);
  ASSERT_TRUE(j.contains("coefficients"));
  EXPECT_EQ(j["unit"], "gauss");
  EXPECT_EQ(j["pipeline"]["columns"]["units"]["gyro"], "T");
  const double offset = j["coefficients"]["1"].get<double>();
  EXPECT_LT(std::abs(offset), 1.0) << "gauss";
  EXPECT_GT(std::abs(offset), 1e-3) << "gauss: the tesla read as gauss would be 1e4 times smaller";
  const CliResult text = run_cli(dir, "fit " + args);
  EXPECT_NE(text.out.find("mag T (header 'mag1x [T]')"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("gauss per °C"), std::string::npos) << text.out;
}

}  // namespace
}  // namespace gyrotherm::fit
