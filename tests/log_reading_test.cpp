// Autopilot logs read by every command (fit/data/measurement.h, read_log):
// a log gives the fit a CSV of the same numbers gives, bit for bit; the gyro
// is chosen as documented; the units are the format's. And the autopilot
// loop closed: a simulated thermal test written as a PX4 ULog and as an
// ArduPilot DataFlash log, fitted from the log, exported, and the export
// applied again by each firmware's rule to the record: the instability equals
// the one export reported.

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "imu_logs.h"
#include "cli_runner.h"
#include "fit/data/autopilot_log.h"
#include "fit/data/measurement.h"
#include "parameter_files.h"
#include "synthetic_log.h"

namespace gyrotherm::testing {
namespace {

// The samples as a CSV of the same numbers (time in s, rates in rad/s).
void write_csv(const std::filesystem::path& file, const std::vector<ImuSample>& samples) {
  std::ofstream out(file);
  out << "time_s,temp_c,gyro_x (rad/s),gyro_y (rad/s),gyro_z (rad/s)\n";
  for (const ImuSample& s : samples)
    out << fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", static_cast<double>(s.time_us) / 1e6,
                       static_cast<double>(s.temp_c), static_cast<double>(s.x), static_cast<double>(s.y),
                       static_cast<double>(s.z));  // each float's value exactly
}

std::vector<ImuSample> synthetic_samples() {
  std::vector<ImuSample> out;
  for (const LogRow& r : synthetic_log()) {
    const auto x = static_cast<float>(r.gyro_dph * kDphToRadS);
    out.push_back({static_cast<std::uint64_t>(r.t * 1e6) + 5000000, static_cast<float>(r.temp_c), x, -x, 0.5f * x});
  }
  return out;
}

TEST(LogReading, ALogGivesTheFitOfACsvOfTheSameNumbers) {
  ScratchDir dir;
  const std::vector<ImuSample> samples = synthetic_samples();
  write_ulog(dir / "t.ulg", samples);
  write_dataflash(dir / "t.bin", samples);
  write_csv(dir / "t.csv", samples);
  const nlohmann::json csv = fit_json(dir, "t.csv --gyro-col 'gyro_x (rad/s),gyro_y (rad/s),gyro_z (rad/s)'");
  for (const char* log : {"t.ulg", "t.bin"}) {
    const nlohmann::json j = fit_json(dir, log);  // the three axes by default
    ASSERT_EQ(j["channels"].size(), 3u) << log;
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_EQ(j["channels"][a]["channel"], std::string("gyro_") + "xyz"[a]);
      EXPECT_EQ(j["channels"][a]["coefficients"], csv["channels"][a]["coefficients"]) << log << " axis " << a;
      EXPECT_EQ(j["channels"][a]["instability_after_dph"], csv["channels"][a]["instability_after_dph"]);
    }
  }
  // The gyro of instance 0 has no temperature: instance 1 is taken, and said.
  const std::string units = fit_json(dir, "t.ulg --gyro-col gyro_z")["data"]["units"];
  EXPECT_NE(units.find("gyro rad/s (ULog v1 sensor_gyro instance 1)"), std::string::npos) << units;
  // The report lists what the log holds: instance 0 without a temperature.
  EXPECT_NE(units.find("(device 2490378) chosen; the log holds ULog v1: sensor_gyro instance 0 (device 2621450): 7200 "
                       "samples"),
            std::string::npos) << units;
  EXPECT_NE(units.find("temperature NaN throughout"), std::string::npos) << units;
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"t.ulg --imu 0", "sensor_gyro instance 0 has 0 samples with a temperature; at least 2 are needed"},
           {"t.ulg --imu 4", "--imu 4: the log holds gyro instances 0 and 1"},
           {"t.ulg --imu -1", "--imu -1: a gyro instance is a number from 0"},
           {"t.bin --gyro-unit dph", "--gyro-unit dph: the log is DataFlash, whose units are fixed"},
           {"t.bin --gyro-scale 2", "--gyro-scale, --temp-scale and --temp-offset are for raw counts"},
           {"t.ulg --gyro-col gx", "no column 'gx' (the header has: time_s, temp_c, gyro_x, gyro_y, gyro_z)"}})
    expect_refused(dir, "fit " + args, expected);
  // A CSV's form does not concern a log; nor do the units a fit made on a CSV in other units brings.
  EXPECT_EQ(fit_json(dir, "t.ulg --decimal-comma --rate 5 --gyro-col gyro_y")["coefficients"],
            csv["channels"][1]["coefficients"]);
  {
    std::ofstream out(dir / "dph.csv");
    out << "time_s,temp_c,gyro_dph\n";
    for (const LogRow& r : synthetic_log()) out << r.t << "," << r.temp_c << "," << r.gyro_dph << "\n";
  }
  const auto dph = run_cli(dir, "fit dph.csv --model T --temp-scale 1 -o dph.json");
  ASSERT_EQ(dph.exit_code, 0) << dph.err;
  const auto applied = run_cli(dir, "compensate --fit dph.json t.ulg --gyro-col gyro_y -o dph_on_log.csv");
  EXPECT_EQ(applied.exit_code, 0) << applied.err;
  // A saved fit keeps the gyro it was made on; compensate reads the log again.
  ASSERT_EQ(run_cli(dir, "fit t.ulg --imu 1 --gyro-col gyro_x -o fit.json").exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "fit.json"))["pipeline"]["columns"]["imu"], 1);
  EXPECT_EQ(run_cli(dir, "compensate --fit fit.json t.ulg -o out.csv").exit_code, 0);
}

// The registry (fit/data/log_formats.def): each format is known by its first
// bytes alone, no format's magic begins another's, a file the registry does
// not know is a text table, and each format's reader reads its own file.
TEST(LogReading, EachRegisteredFormatIsKnownByItsFirstBytes) {
  ScratchDir dir;
  const std::vector<fit::LogFormat>& formats = fit::log_format_registry();
  ASSERT_EQ(formats.size(), 2u);
  for (const fit::LogFormat& a : formats) {
    EXPECT_FALSE(a.magic.empty()) << a.name;
    for (const fit::LogFormat& b : formats)
      EXPECT_TRUE(&a == &b || !b.magic.starts_with(a.magic)) << a.name << " begins " << b.name;
    const std::filesystem::path file = dir / std::string(a.name);
    std::ofstream(file, std::ios::binary) << a.magic << "not a message";
    EXPECT_EQ(fit::log_format_of(file), &a) << a.name;
  }
  std::ofstream(dir / "t.csv") << "time_s,temp_c,gyro\n0,20,1\n";
  EXPECT_EQ(fit::log_format_of(dir / "t.csv"), nullptr);
  EXPECT_EQ(fit::log_format_of(dir / "absent.bin"), nullptr);
  const std::vector<ImuSample> samples = synthetic_samples();
  write_ulog(dir / "t.ulg", samples);
  write_dataflash(dir / "t.bin", samples);
  for (const auto& [file, name, title] : {std::tuple{"t.ulg", "ulog", "ULog v1"}, {"t.bin", "dataflash", "DataFlash"}}) {
    const fit::LogFormat* format = fit::log_format_of(dir / file);
    ASSERT_NE(format, nullptr) << file;
    EXPECT_EQ(format->name, name);
    const fit::LogContents contents = format->read(dir / file, -1, {}, fit::sensor_kind("gyro"));
    EXPECT_EQ(contents.format, title);
    EXPECT_TRUE(fit::stated_by_log_format(contents.format + " sensor_gyro instance 1"));
    EXPECT_EQ(contents.sensors.back().samples, samples.size()) << file;
  }
  EXPECT_FALSE(fit::stated_by_log_format("the header of column gyro_x"));
}

TEST(LogReading, TheRealPx4LogsReadAsTheirReadmeSays) {
  const std::string folder = source_path("../shared/data/real/px4_ulog/");
  if (!std::filesystem::exists(folder + "quadrotor_local.ulg")) GTEST_SKIP() << "no PX4 sample logs";
  ScratchDir dir;
  const nlohmann::json j = fit_json(dir, folder + "quadrotor_local.ulg --gyro-col gyro_z --avg 5");
  EXPECT_EQ(j["data"]["raw_samples"], 92);
  EXPECT_NE(j["data"]["units"].get<std::string>().find("sensor_gyro instance 1 (device 2490378)"), std::string::npos);
  const nlohmann::json small = fit_json(dir, folder + "sample_log_small.ulg --gyro-col gyro_x --imu 2 --avg 1");
  EXPECT_EQ(small["data"]["raw_samples"], 6);
  // Instance 2's samples span 29.43..29.72 °C: its window means lie within.
  EXPECT_GE(small["data"]["temp_range_c"][0].get<double>(), 29.43);
  EXPECT_LE(small["data"]["temp_range_c"][1].get<double>(), 29.73);
}

// The simulated cycle as a MEMS gyro on an autopilot (20 °/h per °C and a
// curvature on x), written by each firmware's logger, fitted from the log
// and exported for that firmware: applying the exported file by the
// firmware's rule to the record gives the instability export reported.
TEST(LogReading, TheAutopilotLoopClosesOnEachFirmwaresLog) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "d.csv");
  std::vector<ImuSample> samples;
  const fit::Measurement record = fit::read_measurement_csv(dir / "d.csv");
  for (std::size_t i = 0; i < record.size(); ++i) {
    const fit::Measurement& m = record;
    const double temp = m.temp_c[i], dph = m.gyro_dph[i] + 20.0 * temp + 0.05 * temp * temp;
    const auto x = static_cast<float>(dph * kDphToRadS);
    samples.push_back({static_cast<std::uint64_t>(std::llround(m.time_s[i] * 1e6)), static_cast<float>(temp), x,
                       0.5f * x, -x});
  }
  write_ulog(dir / "px4.ulg", samples);
  write_dataflash(dir / "ap.bin", samples);
  for (const auto& [log, format, boot] : {std::tuple{"px4.ulg", "px4", ""}, {"ap.bin", "ardupilot", "--boot-temp 25"}}) {
    ASSERT_EQ(run_cli(dir, fmt::format("fit {} --model 'T + T^2' -o {}.json", log, format)).exit_code, 0);
    const auto r = run_cli(dir, fmt::format("export {0}.json --format {0} {1} --json -o {0}.par", format, boot));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json outcome = nlohmann::json::parse(r.out)["firmware_outcome"];
    EXPECT_EQ(outcome["data"], log);
    const std::string text = slurp(dir / (std::string(format) + ".par"));
    for (int a = 0; a < 3; ++a) {
      fit::ColumnMap map;
      map.gyro = std::string("gyro_") + "xyz"[a];
      const fit::Measurement m = fit::read_measurement_csv(dir / log, map);
      std::vector<double> applied;
      if (std::string(format) == "px4") {
        applied = px4_as_applied(m, read_qgc(text), a);
      } else {
        const auto parameters = read_ap(text);
        for (const double temp : m.temp_c)
          applied.push_back(ardupilot_subtracted(parameters, "XYZ"[a], static_cast<float>(temp), 25.0f) / kDphToRadS);
      }
      const double expected = instability(m, applied);
      EXPECT_NEAR(outcome["axes"][a]["firmware_dph"].get<double>(), expected, 1e-9 * expected) << format << " " << a;
    }
  }
}

}  // namespace
}  // namespace gyrotherm::testing
