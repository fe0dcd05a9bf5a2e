// Units written in the header (fit/data/header_units.h) and the plausibility
// of what was read (fit/data/plausibility.h): every form loggers write is
// read, an option that contradicts the header is an error naming both, a
// record written in other units gives the plain CSV's fit, and numbers that
// look like another unit are cautioned.

#include "fit/data/header_units.h"

#include <gtest/gtest.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "cli_runner.h"
#include "expect_input_error.h"
#include "fit/data/plausibility.h"
#include "synthetic_log.h"

namespace gyrotherm::fit {
namespace {

using testing::expect_input_error;
using testing::run_cli;
using testing::ScratchDir;
using testing::write_text;
using testing::fit_json;
using testing::LogRow;
using testing::synthetic_log;

std::string named(Quantity q, std::string_view column) {
  const HeaderUnit h = unit_in_header(q, column);
  return h.unit ? std::string(h.unit->name) : h.raw_counts ? "counts" : h.unknown() ? "?" + h.said : "";
}

TEST(HeaderUnits, EveryFormLoggersWriteIsRead) {
  using Q = Quantity;
  EXPECT_EQ(named(Q::time, "time (ms)"), "ms");
  EXPECT_EQ(named(Q::time, "t_us"), "us");
  EXPECT_EQ(named(Q::time, "time_s"), "s");
  EXPECT_EQ(named(Q::time, "Time [µs]"), "us");
  EXPECT_EQ(named(Q::time, "timestamp ns"), "ns");
  EXPECT_EQ(named(Q::time, "elapsed (h)"), "h");
  EXPECT_EQ(named(Q::gyro, "gyro [rad/s]"), "rad/s");
  EXPECT_EQ(named(Q::gyro, "gyrox rad/s"), "rad/s");
  EXPECT_EQ(named(Q::gyro, "gyro_rad_s"), "rad/s");
  EXPECT_EQ(named(Q::gyro, "gx_dps"), "dps");
  EXPECT_EQ(named(Q::gyro, "wz (°/s)"), "dps");
  EXPECT_EQ(named(Q::gyro, "gyro_dph"), "dph");
  EXPECT_EQ(named(Q::gyro, "rate [deg/h]"), "dph");
  EXPECT_EQ(named(Q::gyro, "gyro (mrad/s)"), "mrad/s");
  EXPECT_EQ(named(Q::temperature, "temp (K)"), "K");
  EXPECT_EQ(named(Q::temperature, "temp_c"), "C");
  EXPECT_EQ(named(Q::temperature, "Temperature (°C)"), "C");
  EXPECT_EQ(named(Q::temperature, "T [degF]"), "F");
  // Nothing said: a suffix or word that is no unit of the column's quantity.
  EXPECT_EQ(named(Q::gyro, "gyro_x"), "");
  EXPECT_EQ(named(Q::gyro, "gyro_s"), "");  // s is a time unit, not a rate
  EXPECT_EQ(named(Q::temperature, "temp sensor"), "");
  EXPECT_EQ(named(Q::temperature, "temp"), "");
  // Said but not known, and raw counts.
  EXPECT_EQ(named(Q::gyro, "gyro (furlongs/fortnight)"), "?furlongs/fortnight");
  EXPECT_EQ(named(Q::temperature, "temp [LSB]"), "counts");
}

TEST(HeaderUnits, TheOptionWinsOnlyWhereTheHeaderAgreesOrIsSilent) {
  Units asked;
  Units r = resolve_units(asked, "time (ms)", "temp_c", "gyrox rad/s", "");
  EXPECT_EQ(r.time, "ms");
  EXPECT_EQ(r.gyro, "rad/s");
  EXPECT_EQ(r.temp, "C");
  EXPECT_EQ(r.time_from, "header 'time (ms)'");
  r = resolve_units(asked, "t", "temp", "g", "");
  EXPECT_EQ(r.time, "s");
  EXPECT_EQ(r.time_from, "default");
  EXPECT_EQ(r.used(), "time s (default), gyro dph (default), temperature C (default)");

  asked.time = "us";  // silent header: the option
  EXPECT_EQ(resolve_units(asked, "t", "temp", "g", "").time_from, "--time-unit");
  expect_input_error([&] { resolve_units(asked, "time (ms)", "temp", "g", ""); },
                     {"'time (ms)'", "ms (milliseconds)", "--time-unit gives us (microseconds)"});
  asked = {};
  asked.temp = "K";
  expect_input_error([&] { resolve_units(asked, "t", "temp_c", "g", ""); }, {"'temp_c'", "--temp-unit gives K"});
  // The two temperature columns share one unit.
  expect_input_error([&] { resolve_units(Units{}, "t", "temp (C)", "g", "temp2 (K)"); },
                     {"different units", "'temp2 (K)'"});
  EXPECT_EQ(resolve_units(Units{}, "t", "temp", "g", "temp2 (K)").temp, "K");
  // Unknown units and raw counts ask for the option that settles them.
  expect_input_error([&] { resolve_units(Units{}, "t", "temp", "gyro (furlongs)", ""); },
                     {"'gyro (furlongs)'", "furlongs", "--gyro-unit"});
  Units given;
  given.gyro = "dps";
  EXPECT_EQ(resolve_units(given, "t", "temp", "gyro (furlongs)", "").gyro, "dps");
  expect_input_error([&] { resolve_units(Units{}, "t", "temp [LSB]", "g", ""); },
                     {"raw counts", "--temp-scale and --temp-offset"});
  Units scaled;
  scaled.temp_scale = 0.00390625;
  EXPECT_EQ(resolve_units(scaled, "t", "temp [LSB]", "g", "").temp, "C");
}

TEST(HeaderUnits, ARecordWrittenInOtherUnitsGivesThePlainFit) {
  ScratchDir dir;
  std::string plain = "time_s,temp_c,gyro_dph\n", other = "time (ms),temp (K),gyro [rad/s]\n";
  constexpr double kDphPerRadS = 3600.0 * 180.0 / M_PI;
  for (const LogRow& r : synthetic_log()) {
    plain += fmt::format("{:.17g},{:.17g},{:.17g}\n", r.t, r.temp_c, r.gyro_dph);
    other += fmt::format("{:.17g},{:.17g},{:.17g}\n", 1000.0 * r.t, r.temp_c + 273.15, r.gyro_dph / kDphPerRadS);
  }
  write_text(dir / "plain.csv", plain);
  write_text(dir / "other.csv", other);
  const nlohmann::json a = fit_json(dir, "plain.csv");
  const nlohmann::json b = fit_json(dir, "other.csv --time-col 'time (ms)' --temp-col 'temp (K)' --gyro-col 'gyro [rad/s]'");
  ASSERT_FALSE(a.is_null());
  ASSERT_FALSE(b.is_null());
  EXPECT_NEAR(b["coefficients"]["T"].get<double>(), a["coefficients"]["T"].get<double>(),
              1e-9 * std::abs(a["coefficients"]["T"].get<double>()));
  EXPECT_NEAR(b["instability_after_dph"].get<double>(), a["instability_after_dph"].get<double>(),
              1e-9 * a["instability_after_dph"].get<double>());
  EXPECT_EQ(b["data"]["units"], "time ms (header 'time (ms)'), gyro rad/s (header 'gyro [rad/s]'), "
                                "temperature K (header 'temp (K)')");
  EXPECT_TRUE(b["data"]["cautions"].empty()) << b["data"]["cautions"];
  // The fit file keeps the units it read in, and says where they came from.
  EXPECT_EQ(b["pipeline"]["columns"]["units"]["time"], "ms");
  EXPECT_EQ(b["pipeline"]["columns"]["units"]["from"]["gyro"], "header 'gyro [rad/s]'");
  // An option that contradicts the header stops with both named, exit 2.
  const auto clash = run_cli(dir, "fit other.csv --time-col 'time (ms)' --temp-col 'temp (K)' --gyro-col "
                                  "'gyro [rad/s]' --gyro-unit dps");
  EXPECT_EQ(clash.exit_code, 2);
  EXPECT_NE(clash.err.find("'gyro [rad/s]' states its unit as rad/s"), std::string::npos) << clash.err;
  EXPECT_NE(clash.err.find("--gyro-unit gives dps"), std::string::npos) << clash.err;
  // A unit the header states that is none of gyrotherm's, and raw counts without a scale: exit 2, the option named.
  testing::write_text(dir / "odd.csv", "time_s,temp [LSB],gyro (furlongs)\n0,5000,1\n1,5001,2\n");
  testing::expect_refused(dir, "fit odd.csv --temp-col 'temp [LSB]' --gyro-col 'gyro (furlongs)' --gyro-unit dph",
                          "column 'temp [LSB]' holds raw counts (LSB): give --temp-scale and --temp-offset");
  testing::expect_refused(dir, "fit odd.csv --temp-col 'temp [LSB]' --gyro-col 'gyro (furlongs)' --temp-scale 0.01",
                          "column 'gyro (furlongs)' states the unit 'furlongs'");
}

TEST(HeaderUnits, NumbersThatLookLikeAnotherUnitAreCautioned) {
  ScratchDir dir;
  // The same record with silent headers, each column in another unit than it is read in.
  std::string rad = "time,temp,gyro\n", ms = "time,temp,gyro\n";
  for (const LogRow& r : synthetic_log()) {
    rad += fmt::format("{},{:.6f},{:.9g}\n", r.t, r.temp_c, r.gyro_dph / 206264.806);
    ms += fmt::format("{},{:.6f},{:.6f}\n", 1000.0 * r.t, r.temp_c, r.gyro_dph);
  }
  write_text(dir / "rad.csv", rad);
  write_text(dir / "ms.csv", ms);
  const std::string cols = " --time-col time --temp-col temp --gyro-col gyro";
  const nlohmann::json a = fit_json(dir, "rad.csv" + cols);
  ASSERT_EQ(a["data"]["cautions"].size(), 1u) << a["data"]["cautions"];
  EXPECT_NE(a["data"]["cautions"][0].get<std::string>().find("quieter than any gyro"), std::string::npos);
  // °C read as K: −248 °C is no test a gyro sees.
  const nlohmann::json k = fit_json(dir, "rad.csv" + cols + " --temp-unit K --gyro-unit rad/s");
  ASSERT_EQ(k["data"]["cautions"].size(), 1u) << k["data"]["cautions"];
  EXPECT_NE(k["data"]["cautions"][0].get<std::string>().find("below -100 °C"), std::string::npos);
  EXPECT_NE(k["data"]["cautions"][0].get<std::string>().find("°C read as kelvin (give --temp-unit C)"),
            std::string::npos)
      << k["data"]["cautions"][0];
  // Kelvin under a name that says °C: --temp-unit K contradicts the name, and
  // the refusal names the offset that reads them.
  write_text(dir / "kc.csv", "time_s,temp_c,gyro_dph\n0,293.15,1\n1,293.2,1\n2,293.3,1\n");
  testing::expect_refused(dir, "fit kc.csv --temp-unit K",
                 "column 'temp_c' states its unit as C (degrees Celsius), but --temp-unit gives K (kelvin)");
  testing::expect_refused(dir, "fit kc.csv --temp-unit K",
                 "if the numbers are kelvin under a name that says °C, give --temp-offset -273.15 instead");
  // A 2 h test read as 83 days.
  const nlohmann::json t = fit_json(dir, "ms.csv --avg 20000" + cols);
  ASSERT_GE(t["data"]["cautions"].size(), 1u);
  EXPECT_NE(t["data"]["cautions"][0].get<std::string>().find("spans 83 days"), std::string::npos)
      << t["data"]["cautions"];
  // With the default window the samples are 1000 s apart: the refusal says why.
  const auto refused = run_cli(dir, "fit ms.csv" + cols);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("the averaging window is shorter than the sample interval"), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("caution (how the record was read): the record spans 83 days"), std::string::npos)
      << refused.err;
  // A smooth turn at up to 47 °/s (sample-to-sample changes small): the
  // rates no gyro at rest reads are cautioned.
  std::string turn = "time,temp,gyro\n";
  for (const LogRow& r : synthetic_log())
    turn += fmt::format("{},{:.6f},{:.6f}\n", r.t, r.temp_c, 47.0 * 3600.0 * std::sin(2.0 * M_PI * r.t / 600.0));
  write_text(dir / "turn.csv", turn);
  const nlohmann::json m = fit_json(dir, "turn.csv" + cols);
  ASSERT_EQ(m["data"]["cautions"].size(), 1u) << m["data"]["cautions"];
  EXPECT_NE(m["data"]["cautions"][0].get<std::string>().find("reads more than 10 °/s on"), std::string::npos)
      << m["data"]["cautions"];
  EXPECT_NE(m["data"]["cautions"][0].get<std::string>().find("up to 47 °/s"), std::string::npos);
  // Read right, nothing is cautioned, and the text says which units were used.
  const auto text = run_cli(dir, "fit rad.csv" + cols + " --gyro-unit rad/s --model T");
  EXPECT_EQ(text.out.find("caution: the gyro"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("units: time s (default), gyro rad/s (--gyro-unit), temperature C (default)"),
            std::string::npos)
      << text.out;
}

TEST(HeaderUnits, ThePanLogsOwnHeaderIsReadAsItsFlightSoftwareWroteIt) {
  const std::filesystem::path raw = std::string(GYROTHERM_SOURCE_DIR) + "/../shared/data/real/pan_tvac/TVCtest3_7_20.csv";
  const std::filesystem::path converted = raw.parent_path() / "pan_tvac_3axis.csv";
  if (!std::filesystem::exists(raw) || !std::filesystem::exists(converted)) GTEST_SKIP() << "no PAN log";
  ScratchDir dir;
  // Only the raw counts and the logger's 2x scale bug need saying; ms and rad/s are in the header.
  const nlohmann::json a = fit_json(dir, "'" + raw.string() + "' --time-col 'time (ms)' --gyro-col 'gyrox rad/s' "
                                         "--temp-col temp --temp-scale 0.00390625 --temp-offset -231 --gyro-scale 0.5");
  const nlohmann::json b = fit_json(dir, "'" + converted.string() + "' --gyro-col gx_dph");
  ASSERT_FALSE(a.is_null());
  ASSERT_FALSE(b.is_null());
  EXPECT_EQ(a["data"]["sample_interval_s"], b["data"]["sample_interval_s"]);
  EXPECT_NEAR(a["coefficients"]["T"].get<double>(), b["coefficients"]["T"].get<double>(),
              1e-3 * std::abs(b["coefficients"]["T"].get<double>()));
}

}  // namespace
}  // namespace gyrotherm::fit
