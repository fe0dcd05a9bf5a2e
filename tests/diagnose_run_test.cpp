// studies/diagnose/diagnose_run.h: progress where the work is long (a large
// log, whether held in memory or streamed), none on a small one.

#include "studies/diagnose/diagnose_run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cli_runner.h"
#include "fit/model/formula.h"

namespace gyrotherm::studies {
namespace {

using namespace gyrotherm::testing;

DiagnoseRequest request_for(const std::filesystem::path& csv, std::vector<std::pair<std::string, double>>* calls) {
  DiagnoseRequest r;
  r.data = csv.string();
  r.base_terms = r.terms = fit::parse_formula("T");
  r.progress = [calls](const std::string& step, double fraction) { calls->emplace_back(step, fraction); };
  return r;
}

TEST(DiagnoseRun, ProgressOnALargeLogHeldInMemoryNotOnASmallOne) {
  ScratchDir dir;
  {
    std::ofstream out(dir / "log.csv");
    out << "time_s,temp_c,gyro_dph\n";
    for (int k = 0; k < 3 * 3600; ++k) out << k << "," << 10.0 + k / 540.0 << "," << std::sin(k * 0.37) << "\n";
  }
  std::vector<std::pair<std::string, double>> calls;
  run_diagnose(request_for(dir / "log.csv", &calls));
  EXPECT_TRUE(calls.empty()) << "a small log: no progress";

  DiagnoseRequest large = request_for(dir / "log.csv", &calls);
  large.progress_above_bytes = 1000;  // this log counts as large
  const DiagnoseRun run = run_diagnose(large);
  ASSERT_FALSE(run.channels.front().streamed) << "held in memory, not streamed";
  ASSERT_GE(calls.size(), 3u);
  EXPECT_NE(calls.front().first.find("reading"), std::string::npos) << calls.front().first;
  EXPECT_EQ(calls.back().second, 1.0) << calls.back().first;
  for (std::size_t k = 1; k < calls.size(); ++k) EXPECT_GE(calls[k].second, calls[k - 1].second) << calls[k].first;
}

}  // namespace
}  // namespace gyrotherm::studies
