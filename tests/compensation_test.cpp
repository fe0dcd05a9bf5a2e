// compensate_streaming (the path for logs too large to hold) against
// compensate() and write_compensated_csv on the same record.

#include "fit/compensation.h"

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "fit/pipeline.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

// On a record within the streaming prefix the windows are those of the
// in-memory pipeline, so the output file must be the same, byte for byte, in
// both modes, and so must the report.
TEST(Compensation, StreamedOutputIsTheInMemoryOutput) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  ASSERT_EQ(run_cli(dir, "fit c.csv --model 'T + T^2 + dT' -o fit.json").exit_code, 0);
  const SavedFit fit = load_fit(dir / "fit.json");
  for (const DerivativeMode mode : {DerivativeMode::central, DerivativeMode::causal}) {
    PipelineOptions p = reading_columns_of(fit.pipeline, fit.terms);
    p.derivative = mode;
    const Compensation held = compensate(read_measurement_csv(dir / "c.csv", p.columns), fit, p);
    write_compensated_csv(dir / "held.csv", held);
    const Compensation streamed = compensate_streaming(dir / "c.csv", fit, p, dir / "streamed.csv");
    EXPECT_GT(held.data.outliers.removed + held.time_s.size(), 30000u);
    EXPECT_EQ(slurp(dir / "streamed.csv"), slurp(dir / "held.csv")) << to_string(mode);
    EXPECT_EQ(streamed.before_dph, held.before_dph);
    EXPECT_EQ(streamed.after_dph, held.after_dph);
    EXPECT_EQ(streamed.data.outliers.times_s, held.data.outliers.times_s);
    EXPECT_TRUE(streamed.time_s.empty());  // nothing held at full rate
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().string().find(".rows.tmp"), std::string::npos) << "left behind: " << entry.path();
}

// A bad row in the middle: the error names it, and neither the output nor the
// temporary file of rows is left.
TEST(Compensation, StreamedBadRowLeavesNoFiles) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  ASSERT_EQ(run_cli(dir, "fit c.csv -o fit.json").exit_code, 0);
  std::string text = slurp(dir / "c.csv");
  const std::size_t at = text.find("\n20000,");
  ASSERT_NE(at, std::string::npos);
  text.replace(at + 1, 5, "abcde");
  gyrotherm::testing::write_text(dir / "bad.csv", text);
  const SavedFit fit = load_fit(dir / "fit.json");
  const PipelineOptions p = reading_columns_of(fit.pipeline, fit.terms);
  const std::size_t files = dir.file_count();
  try {
    compensate_streaming(dir / "bad.csv", fit, p, dir / "out.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'abcde' is not a number"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.file_count(), files);
}

TEST(Compensation, StreamedRecordWithGlitchesFlagsThemAtTheirRows) {
  ScratchDir dir;
  simulate_shipped(dir, "cycle", "", "c.csv");
  ASSERT_EQ(run_cli(dir, "fit c.csv -o fit.json").exit_code, 0);
  // Three counting glitches written into the record.
  std::string text = slurp(dir / "c.csv");
  std::size_t glitches = 0;
  for (const char* row : {"\n5000,", "\n12000,", "\n30000,"}) {
    const std::size_t at = text.find(row);
    ASSERT_NE(at, std::string::npos);
    std::size_t gyro = at + 1;  // after the fifth comma: gyro_dph
    for (int comma = 0; comma < 5; ++comma) gyro = text.find(',', gyro) + 1;
    text.replace(gyro, text.find(',', gyro) - gyro, "40.0");  // tens of °/h off
    ++glitches;
  }
  gyrotherm::testing::write_text(dir / "g.csv", text);
  const SavedFit fit = load_fit(dir / "fit.json");
  const PipelineOptions p = reading_columns_of(fit.pipeline, fit.terms);
  const Compensation held = compensate(read_measurement_csv(dir / "g.csv", p.columns), fit, p);
  ASSERT_GE(held.data.outliers.removed, glitches);
  write_compensated_csv(dir / "held.csv", held);
  compensate_streaming(dir / "g.csv", fit, p, dir / "streamed.csv");
  EXPECT_EQ(slurp(dir / "streamed.csv"), slurp(dir / "held.csv"));
}

}  // namespace
}  // namespace gyrotherm::fit
