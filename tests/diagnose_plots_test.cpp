// studies/diagnose/diagnose_plots.h: where the plots against time break their
// lines (the record's gaps), and that the figures draw with the breaks.

#include "studies/diagnose/diagnose_plots.h"

#include <gtest/gtest.h>

#include <cmath>

#include <fmt/format.h>

#include "cli_runner.h"
#include "fit/pipeline.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;

// 1 Hz samples over [0, 3 h) with the seconds in `holes` left out.
fit::Measurement record_with_holes(const std::vector<std::pair<int, int>>& holes) {
  fit::Measurement m;
  m.file = "holes.csv";
  for (int k = 0; k < 3 * 3600; ++k) {
    bool in_hole = false;
    for (const auto& [from, to] : holes) in_hole |= k >= from && k < to;
    if (in_hole) continue;
    m.time_s.push_back(k);
    m.temp_c.push_back(20.0 + k / 600.0);
    m.gyro_dph.push_back(std::sin(k / 50.0));
  }
  return m;
}

TEST(DiagnosePlots, LinesBreakAtAGapNotAtADropout) {
  // A 40 min hole after the first hour: the first window after it starts a new line.
  const fit::PreparedData gap = fit::prepare_data(record_with_holes({{3600, 6000}}), {});
  const std::vector<std::size_t> breaks = windows_after_gaps(gap);
  ASSERT_EQ(breaks.size(), 1u);
  EXPECT_LT(gap.series.time_s[breaks[0] - 1], 3600.0);
  EXPECT_GT(gap.series.time_s[breaks[0]], 6000.0);
  // A few seconds missing here and there: a line as measured.
  const fit::PreparedData dropouts = fit::prepare_data(record_with_holes({{1000, 1005}, {5000, 5004}}), {});
  EXPECT_TRUE(windows_after_gaps(dropouts).empty());
}

TEST(DiagnosePlots, AGappedRecordIsDrawn) {
  ScratchDir dir;
  const fit::Measurement m = record_with_holes({{3600, 6000}});
  std::string csv = "time_s,temp_c,gyro_dph\n";
  for (std::size_t k = 0; k < m.size(); ++k)
    csv += fmt::format("{},{},{}\n", m.time_s[k], m.temp_c[k], m.gyro_dph[k]);
  write_text(dir / "holes.csv", csv);
  const auto r = run_cli(dir, "diagnose holes.csv --model T --plots figs");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* png : {"bias_time.png", "residual_segments.png"})
    EXPECT_GT(std::filesystem::file_size(dir / "figs" / png), 10000u) << png;
}

}  // namespace
}  // namespace gyrotherm::studies
