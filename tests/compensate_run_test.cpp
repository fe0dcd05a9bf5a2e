// `compensate` on a log whose columns are named (and written) differently
// from the fit's (studies/fit/compensate_run.h): the column and unit options
// of `fit` name them, and the result is the one on the fit's own log.

#include "studies/fit/compensate_run.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;

TEST(CompensateRun, TheFitsColumnsCanBeRenamedAndRewritten) {
  ScratchDir dir;
  simulate_shipped(dir, "warmup", "", "log.csv");
  // The same record with time in ms under another name, and the gyro column renamed.
  ASSERT_EQ(run_shell(dir, "awk -F, 'BEGIN{OFS=\",\"} /^#/{next} /^time/{$1=\"t (ms)\"; $6=\"rate\"; print; next} "
                           "{$1=$1*1000; print}' log.csv | tee other.csv").exit_code,
            0);
  ASSERT_EQ(run_cli(dir, "fit log.csv -o fit.json").exit_code, 0);
  const auto same = run_cli(dir, "compensate log.csv --fit fit.json --json");
  ASSERT_EQ(same.exit_code, 0) << same.err;
  // Without the names the reader says which option names them.
  expect_refused(dir, "compensate other.csv --fit fit.json", "name the time column with --time-col");
  // The fit's s came from its record's default, not from an option: this
  // record's header (ms) wins, as --time-unit ms would say.
  const auto by_header = run_cli(dir, "compensate other.csv --fit fit.json --time-col 't (ms)' --gyro-col rate --json");
  ASSERT_EQ(by_header.exit_code, 0) << by_header.err;
  EXPECT_EQ(nlohmann::json::parse(by_header.out)["instability_after_dph"],
            nlohmann::json::parse(same.out)["instability_after_dph"]);
  // A unit typed when fitting carries over as given: then the header's ms contradicts it.
  ASSERT_EQ(run_cli(dir, "fit log.csv --time-unit s -o typed.json").exit_code, 0);
  expect_refused(dir, "compensate other.csv --fit typed.json --time-col 't (ms)' --gyro-col rate",
                 "the fit file typed.json, --time-unit when fitting gives s");
  const auto renamed =
      run_cli(dir, "compensate other.csv --fit fit.json --time-col 't (ms)' --time-unit ms --gyro-col rate --json");
  ASSERT_EQ(renamed.exit_code, 0) << renamed.err;
  const auto a = nlohmann::json::parse(same.out), b = nlohmann::json::parse(renamed.out);
  EXPECT_NEAR(b["instability_after_dph"].get<double>(), a["instability_after_dph"].get<double>(),
              1e-9 * a["instability_after_dph"].get<double>());
  // allan --fit takes the same column and unit options over the fit's.
  const auto allan_same = run_cli(dir, "allan log.csv --fit fit.json --json");
  const auto allan_renamed =
      run_cli(dir, "allan other.csv --fit fit.json --time-col 't (ms)' --time-unit ms --gyro-col rate --json");
  ASSERT_EQ(allan_renamed.exit_code, 0) << allan_renamed.err;
  const auto as = nlohmann::json::parse(allan_same.out), ar = nlohmann::json::parse(allan_renamed.out);
  ASSERT_EQ(ar["series"].size(), 2u);
  EXPECT_EQ(ar["series"][1]["samples"], as["series"][1]["samples"]);
  const auto adev_renamed = ar["series"][1]["adev_dph"].get<std::vector<double>>();
  const auto adev_same = as["series"][1]["adev_dph"].get<std::vector<double>>();
  ASSERT_EQ(adev_renamed.size(), adev_same.size());
  for (std::size_t i = 0; i < adev_same.size(); ++i) EXPECT_NEAR(adev_renamed[i], adev_same[i], 1e-6 * adev_same[i]);
  // One column per channel.
  expect_refused(dir, "compensate other.csv --fit fit.json --time-col 't (ms)' --time-unit ms --gyro-col rate,x",
                 "2 columns for the 1 channel");
}

// A fit on the warm-up applied to the cycle, which goes far beyond the
// warm-up's range: the windows outside are counted and said, and the model is
// held at the range's edge (offline and real time alike) unless
// --extrapolate, as the firmwares hold their polynomial at TMIN/TMAX.
TEST(CompensateRun, OutsideTheFittedRangeTheModelIsHeldAtTheEdgeAndSaysSo) {
  ScratchDir dir;
  simulate_shipped(dir, "warmup", "", "warm.csv");
  simulate_shipped(dir, "cycle", "", "cycle.csv");
  ASSERT_EQ(run_cli(dir, "fit warm.csv --model 'T + T^2' -o fit.json").exit_code, 0);
  const nlohmann::json fit = nlohmann::json::parse(slurp(dir / "fit.json"));
  const double hi = fit["data"]["temp_range_c"][1];
  const auto& k = fit["coefficients"];
  const double at_edge = k["1"].get<double>() + hi * (k["T"].get<double>() + hi * k["T^2"].get<double>());
  // The model at the record's hottest row of a compensated CSV.
  const auto hottest_model = [&](const std::string& file) {
    std::ifstream in(dir / file);
    double temp = -1e9, model = 0.0;
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#' || line[0] == 't') continue;
      double v[5];
      if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4]) == 5 && v[1] > temp) {
        temp = v[1];
        model = v[3];
      }
    }
    EXPECT_GT(temp, hi + 5.0);
    return model;
  };
  for (const std::string mode : {"", " --causal"}) {
    const auto held = run_cli(dir, "compensate cycle.csv --fit fit.json -o held.csv" + mode);
    ASSERT_EQ(held.exit_code, 0) << held.err;
    EXPECT_NE(held.out.find("lie outside the temperature range the fit was made on"), std::string::npos) << held.out;
    EXPECT_NE(held.out.find("held at the range's edge"), std::string::npos) << held.out;
    EXPECT_NEAR(hottest_model("held.csv"), at_edge, 1e-6 * std::abs(at_edge) + 1e-9) << mode;
    const auto json = run_cli(dir, "compensate cycle.csv --fit fit.json --json" + mode);
    const nlohmann::json j = nlohmann::json::parse(json.out);
    EXPECT_EQ(j["outside_range"], "held");
    EXPECT_GT(j["windows_outside_range"].get<int>(), 0);
    EXPECT_GT(j["share_outside_range"].get<double>(), 0.1);
    const auto extrapolated = run_cli(dir, "compensate cycle.csv --fit fit.json --extrapolate -o far.csv" + mode);
    ASSERT_EQ(extrapolated.exit_code, 0) << extrapolated.err;
    EXPECT_NE(extrapolated.out.find("extrapolated (--extrapolate)"), std::string::npos) << extrapolated.out;
    EXPECT_GT(std::abs(hottest_model("far.csv") - at_edge), 1e-3 * std::abs(at_edge)) << mode;
  }
  // Within the range nothing is said.
  const auto own = run_cli(dir, "compensate warm.csv --fit fit.json");
  EXPECT_EQ(own.out.find("caution"), std::string::npos) << own.out;
  // The same run with its temperature in kelvin under temp_c (no unit in the
  // name): the units are checked as fit checks them, and every window is
  // outside the fitted range.
  ASSERT_EQ(run_shell(dir, "awk -F, 'BEGIN{OFS=\",\"} /^[0-9]/{$4=$4+273.15} {print}' warm.csv | tee kelvin.csv").exit_code, 0);
  const auto kelvin = run_cli(dir, "compensate kelvin.csv --fit fit.json --json");
  ASSERT_EQ(kelvin.exit_code, 0) << kelvin.err;
  const nlohmann::json k_json = nlohmann::json::parse(kelvin.out);
  ASSERT_EQ(k_json["cautions"].size(), 1u) << kelvin.out;
  EXPECT_NE(k_json["cautions"][0].get<std::string>().find("kelvin read as °C (give --temp-offset -273.15: the column's name says °C)"), std::string::npos);
  EXPECT_DOUBLE_EQ(k_json["share_outside_range"].get<double>(), 1.0);
  const auto k_text = run_cli(dir, "compensate kelvin.csv --fit fit.json");
  EXPECT_NE(k_text.out.find("caution: every temperature is above 200 °C"), std::string::npos) << k_text.out;
}


// Every other command that reads a record with its temperature in kelvin
// under temp_c says what compensate says: diagnose (text and JSON), export
// --data (stderr and JSON warnings), check; a fit refused on it lists why.
TEST(CompensateRun, EveryCommandThatReadsTheRecordChecksItsUnits) {
  ScratchDir dir;
  simulate_shipped(dir, "warmup", "", "warm.csv");
  ASSERT_EQ(run_cli(dir, "fit warm.csv --model 'T + T^2' -o fit.json").exit_code, 0);
  ASSERT_EQ(run_shell(dir, "awk -F, 'BEGIN{OFS=\",\"} /^[0-9]/{$4=$4+273.15} {print}' warm.csv | tee kelvin.csv").exit_code, 0);
  // T and T² are collinear at 300 K: the refusal says what looks wrong.
  expect_refused(dir, "fit kelvin.csv", "caution (how the record was read): every temperature is above 200 °C");
  expect_refused(dir, "diagnose kelvin.csv", "caution (how the record was read): every temperature is above 200 °C");
  const auto diagnosed = run_cli(dir, "diagnose kelvin.csv --model T --json");
  ASSERT_EQ(diagnosed.exit_code, 0) << diagnosed.err;
  const nlohmann::json d_json = nlohmann::json::parse(diagnosed.out);
  ASSERT_EQ(d_json["cautions"].size(), 1u) << d_json["cautions"];
  EXPECT_NE(d_json["cautions"][0].get<std::string>().find("kelvin read as °C (give --temp-offset -273.15: the column's name says °C)"), std::string::npos);
  EXPECT_NE(d_json["units"].get<std::string>().find("temperature C"), std::string::npos) << d_json["units"];
  // --data must be the log the fit was made on: another one is refused, not mixed in.
  expect_refused(dir, "export fit.json --format px4 --data kelvin.csv -o k.params",
                 "--data kelvin.csv: not the log fit.json was fitted on (its SHA-256 differs");
  ASSERT_EQ(run_cli(dir, "fit kelvin.csv --model T -o kfit.json").exit_code, 0);
  const auto exported = run_cli(dir, "export kfit.json --format px4 --data kelvin.csv --accept-caution --json -o k.params");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  // Said once: by the fit's channel (the fit recorded it), not again for --data read a second time.
  EXPECT_NE(exported.err.find("caution: gyro_dph: every temperature is above 200 °C"), std::string::npos) << exported.err;
  EXPECT_EQ(exported.err.find("caution: kelvin.csv: every temperature"), std::string::npos) << exported.err;
  EXPECT_NE(nlohmann::json::parse(exported.out)["warnings"].dump().find("kelvin read as °C (give --temp-offset -273.15: the column's name says °C)"), std::string::npos);
  const auto checked = run_cli(dir, "check kelvin.csv --params k.params --gyro-col gyro_dph --json");
  ASSERT_EQ(checked.exit_code, 0) << checked.err;
  const nlohmann::json c_json = nlohmann::json::parse(checked.out);
  ASSERT_EQ(c_json["cautions"].size(), 1u) << checked.out;
  // The file's own "# CAUTION" block (export --accept-caution) is a finding, with its indented lines.
  bool carried = false;
  for (const auto& f : c_json["findings"])
    if (f["issue"] == "calibration_caution" &&
        f["name"].get<std::string>().find("CAUTION (exported with --accept-caution)") != std::string::npos) {
      carried = true;
      EXPECT_NE(f["name"].get<std::string>().find("every temperature is above 200 °C"), std::string::npos) << f;
      EXPECT_NE(f["text"].get<std::string>().find("the calibration file says: CAUTION"), std::string::npos) << f;
    }
  EXPECT_TRUE(carried) << c_json["findings"];
  EXPECT_NE(c_json["cautions"][0].get<std::string>().find("kelvin read as °C (give --temp-offset -273.15: the column's name says °C)"), std::string::npos);
  // A fit made on it carries the caution into its file, and export stops on
  // it: a firmware would clamp every real temperature to a TMIN near 300 °C.
  const auto refused = run_cli(dir, "export kfit.json --format px4 -o kfit.params");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("look read in another unit"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("kelvin read as °C (give --temp-offset -273.15: the column's name says °C)"), std::string::npos) << refused.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "kfit.params"));
  const auto accepted = run_cli(dir, "export kfit.json --format px4 --accept-caution -o kfit.params");
  ASSERT_EQ(accepted.exit_code, 0) << accepted.err;
  const std::string params = testing::slurp(dir / "kfit.params");
  EXPECT_NE(params.find("# CAUTION (exported with --accept-caution): the data the fit was made on look read in"),
            std::string::npos)
      << params;
  EXPECT_NE(params.find("every temperature is above 200 °C"), std::string::npos) << params;
  // check with that one-channel fit file names its axis by the gyro column.
  const auto one = run_cli(dir, "check kelvin.csv --params kfit.json --json");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ(nlohmann::json::parse(one.out)["axes"][0]["axis"], "gyro_dph");
  // Of a fit file with two channels, an export of one carries that one's
  // cautions only: gyro_b (in rad/s, read as °/h) stops its own export, not gyro_dph's.
  ASSERT_EQ(run_shell(dir, "awk -F, 'BEGIN{OFS=\",\"} /^time/{print $0,\"gyro_b\"; next} /^[0-9]/{print $0, $6/206264.806; "
                           "next} {print}' warm.csv | tee two.csv").exit_code, 0);
  const auto two = run_cli(dir, "fit two.csv --model T --gyro-col gyro_dph,gyro_b -o two.json");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  const auto quiet = run_cli(dir, "export two.json --format c --channel gyro_b -o b.h");
  EXPECT_EQ(quiet.exit_code, 2);
  EXPECT_NE(quiet.err.find("gyro_b: the gyro's sample-to-sample noise"), std::string::npos) << quiet.err;
  const auto clean = run_cli(dir, "export two.json --format c --channel gyro_dph -o a.h");
  ASSERT_EQ(clean.exit_code, 0) << clean.err;
  EXPECT_EQ(testing::slurp(dir / "a.h").find("gyro_b"), std::string::npos);
  // The compensated file of a channel named in rad/s holds °/h: its columns
  // drop the unit the name states ("gyro_b rad/s", or joined by underscores,
  // "gyro_b_rad_s"), and read back as °/h.
  const auto compensated_columns = [&](const std::string& column, const std::string& stem) {
    std::string in_sed;  // the name with its slash escaped for sed
    for (const char c : column) in_sed += c == '/' ? std::string("\\/") : std::string(1, c);
    ASSERT_EQ(run_shell(dir, "sed 's/,gyro_b$/," + in_sed + "/' two.csv | tee " + stem + ".csv").exit_code, 0);
    ASSERT_EQ(run_cli(dir, "fit " + stem + ".csv --model T --gyro-col 'gyro_dph," + column + "' -o " + stem + ".json")
                  .exit_code,
              0);
    ASSERT_EQ(run_cli(dir, "compensate " + stem + ".csv --fit " + stem + ".json -o " + stem + "_out.csv").exit_code, 0);
    const std::string out = testing::slurp(dir / (stem + "_out.csv"));
    EXPECT_NE(out.find(",gyro_b_dph,gyro_b_model_dph,gyro_b_compensated_dph,gyro_b_outlier"), std::string::npos)
        << column << ": " << out.substr(0, 400);
    EXPECT_NE(out.find("time_s,temp_c,gyro_dph,gyro_dph_model_dph,"), std::string::npos) << out.substr(0, 400);
  };
  compensated_columns("gyro_b rad/s", "named");
  compensated_columns("gyro_b_rad_s", "joined");
  const auto back = run_cli(dir, "fit named_out.csv --model T --gyro-col gyro_b_dph");
  ASSERT_EQ(back.exit_code, 0) << back.err;
  EXPECT_NE(back.out.find("gyro dph (header 'gyro_b_dph')"), std::string::npos) << back.out;
}

}  // namespace
}  // namespace gyrotherm::studies
