// `compensate` on a log whose columns are named (and written) differently
// from the fit's (studies/fit/compensate_run.h): the column and unit options
// of `fit` name them, and the result is the one on the fit's own log.

#include "studies/fit/compensate_run.h"

#include <gtest/gtest.h>

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
  // The header's ms contradicts the fit's s: said, and settled by the option.
  expect_refused(dir, "compensate other.csv --fit fit.json --time-col 't (ms)' --gyro-col rate",
                 "the fit file fit.json gives s");
  const auto renamed =
      run_cli(dir, "compensate other.csv --fit fit.json --time-col 't (ms)' --time-unit ms --gyro-col rate --json");
  ASSERT_EQ(renamed.exit_code, 0) << renamed.err;
  const auto a = nlohmann::json::parse(same.out), b = nlohmann::json::parse(renamed.out);
  EXPECT_NEAR(b["instability_after_dph"].get<double>(), a["instability_after_dph"].get<double>(),
              1e-9 * a["instability_after_dph"].get<double>());
  // One column per channel.
  expect_refused(dir, "compensate other.csv --fit fit.json --time-col 't (ms)' --time-unit ms --gyro-col rate,x",
                 "2 columns for the 1 channel");
}

}  // namespace
}  // namespace gyrotherm::studies
