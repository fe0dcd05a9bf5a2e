// The streaming preparation of large records against the in-memory one.

#include "fit/data/streaming.h"

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "sim/config_loader.h"
#include "sim/output.h"
#include "sim/simulator.h"

namespace gyrotherm::fit {
namespace {

using gyrotherm::testing::ScratchDir;
using gyrotherm::testing::source_path;

void simulate_to(const std::filesystem::path& csv, double glitches_per_h, double hours) {
  sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  double t = 0.0;
  std::vector<sim::Segment> kept;
  for (const sim::Segment& s : sc.segments) {  // the first `hours` of the cycle
    if (t >= hours * 3600.0) break;
    kept.push_back(s);
    t += s.kind == sim::SegmentKind::ramp ? 1200.0 : s.duration_s;
  }
  sc.segments = kept;
  sim::GyroConfig gyro = sim::load_gyro(sc.gyro_file);
  gyro.noise.glitch_rate_per_h = glitches_per_h;
  const sim::Simulator simulator(sc, sim::load_rig(sc.rig_file), gyro);
  sim::write_simulation(csv, simulator, simulator.run());
}

TEST(Streaming, SmallRecordIsIdenticalToTheInMemoryPipeline) {
  // Under 20 001 samples the reservoirs hold every step: the same floor, so
  // the same glitches and the same windows.
  ScratchDir dir;
  simulate_to(dir / "r.csv", 20.0, 4.5);
  const PreparedData batch = prepare_data(dir / "r.csv", PipelineOptions{});
  const PreparedData stream = prepare_data_streaming(dir / "r.csv", PipelineOptions{});
  ASSERT_LT(batch.raw_samples, 20001u);
  EXPECT_GT(batch.outliers.removed, 20u);
  EXPECT_EQ(stream.outliers.times_s, batch.outliers.times_s);
  ASSERT_EQ(stream.series.size(), batch.series.size());
  for (std::size_t p = 0; p < batch.series.size(); ++p) {
    EXPECT_NEAR(stream.series.gyro_dph[p], batch.series.gyro_dph[p], 1e-12);
    EXPECT_NEAR(stream.series.temp_c[p], batch.series.temp_c[p], 1e-12);
  }
}

TEST(Streaming, LargeRecordAgreesWithTheInMemoryPipeline) {
  ScratchDir dir;
  simulate_to(dir / "r.csv", 5.0, 24.0);  // the whole cycle, 31 681 samples
  const PreparedData batch = prepare_data(dir / "r.csv", PipelineOptions{});
  const PreparedData stream = prepare_data_streaming(dir / "r.csv", PipelineOptions{});
  EXPECT_GT(batch.raw_samples, 20001u);
  // The floor comes from a sample of the steps here, so it may differ a little;
  // the glitches (±2 °/h against a 0.02 °/h noise) are the same.
  EXPECT_NEAR(stream.outliers.floor_dph / batch.outliers.floor_dph, 1.0, 0.05);
  EXPECT_EQ(stream.outliers.times_s, batch.outliers.times_s);
  ASSERT_EQ(stream.series.size(), batch.series.size());
  for (std::size_t p = 0; p < batch.series.size(); ++p)
    EXPECT_NEAR(stream.series.gyro_dph[p], batch.series.gyro_dph[p], 1e-12);
}

}  // namespace
}  // namespace gyrotherm::fit
