// The one-pass preparation of large records against the in-memory one.

#include "fit/data/streaming.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cli_runner.h"
#include "sim/config_loader.h"
#include "sim/output.h"
#include "sim/simulator.h"
#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

using namespace gyrotherm::testing;

// The first `hours` of the cycle at `rate_hz`, with `glitches_per_h` counting glitches.
void simulate_to(const std::filesystem::path& csv, double glitches_per_h, double hours,
                 double rate_hz = 1.0, double quantization_arcsec = -1.0) {
  sim::Scenario sc = sim::load_scenario(source_path("scenarios/cycle.toml"));
  double t = 0.0;
  std::vector<sim::Segment> kept;
  for (const sim::Segment& s : sc.segments) {
    if (t >= hours * 3600.0) break;
    kept.push_back(s);
    t += s.kind == sim::SegmentKind::ramp ? 1200.0 : s.duration_s;
  }
  sc.segments = kept;
  sc.sample_rate_hz = rate_hz;
  sim::GyroConfig gyro = sim::load_gyro(sc.gyro_file);
  gyro.noise.glitch_rate_per_h = glitches_per_h;
  if (quantization_arcsec >= 0.0) gyro.noise.quantization_arcsec = quantization_arcsec;
  const sim::Simulator simulator(sc, sim::load_rig(sc.rig_file), gyro);
  sim::write_simulation(csv, simulator, simulator.run());
}

void expect_same_series(const PreparedData& a, const PreparedData& b, double tolerance) {
  ASSERT_EQ(a.series.size(), b.series.size());
  for (std::size_t p = 0; p < a.series.size(); ++p) {
    EXPECT_NEAR(a.series.time_s[p], b.series.time_s[p], tolerance) << "window " << p;
    EXPECT_NEAR(a.series.gyro_dph[p], b.series.gyro_dph[p], tolerance) << "window " << p;
    EXPECT_NEAR(a.series.temp_c[p], b.series.temp_c[p], tolerance) << "window " << p;
    EXPECT_EQ(a.series.samples[p], b.series.samples[p]) << "window " << p;
  }
}

TEST(Streaming, RecordWithinThePrefixIsIdenticalToTheInMemoryPipeline) {
  // The whole cycle at 1 Hz (31 681 samples) is within the prefix: the same
  // interval, floor, glitches, scale and windows, to the last bit.
  ScratchDir dir;
  simulate_to(dir / "r.csv", 20.0, 24.0);
  const PreparedData batch = prepare_data(dir / "r.csv", PipelineOptions{});
  const PreparedData stream = prepare_data_streaming(dir / "r.csv", PipelineOptions{});
  ASSERT_LT(batch.raw_samples, kPrefixRows);
  EXPECT_EQ(stream.raw_samples, batch.raw_samples);
  EXPECT_GT(batch.outliers.removed, 200u);
  EXPECT_EQ(stream.outliers.times_s, batch.outliers.times_s);
  EXPECT_EQ(stream.outliers.floor_dph, batch.outliers.floor_dph);
  EXPECT_EQ(stream.outliers.scale_dph, batch.outliers.scale_dph);
  EXPECT_EQ(stream.averaging.sample_interval_s, batch.averaging.sample_interval_s);
  EXPECT_EQ(stream.averaging.median_run_s, batch.averaging.median_run_s);
  EXPECT_EQ(stream.averaging.dropped_windows, batch.averaging.dropped_windows);
  expect_same_series(stream, batch, 0.0);
  ASSERT_EQ(stream.derived.size(), batch.derived.size());
  for (std::size_t p = 0; p < batch.derived.size(); ++p)
    EXPECT_EQ(stream.derived.rate_c_per_s[p], batch.derived.rate_c_per_s[p]);
}

TEST(Streaming, RecordLongerThanThePrefixAgreesWithTheInMemoryPipeline) {
  // 8 h at 10 Hz: 288 001 samples, beyond the prefix, so the floor is that of
  // the first kPrefixRows samples; the glitches (±2 °/h against a 0.05 °/h
  // noise, with a pulse of 0.05 °/h at 10 Hz) and the windows are the same.
  ScratchDir dir;
  simulate_to(dir / "r.csv", 10.0, 8.0, 10.0, 0.005);
  const PreparedData batch = prepare_data(dir / "r.csv", PipelineOptions{});
  const PreparedData stream = prepare_data_streaming(dir / "r.csv", PipelineOptions{});
  ASSERT_GT(batch.raw_samples, kPrefixRows);
  EXPECT_EQ(stream.raw_samples, batch.raw_samples);
  EXPECT_NEAR(stream.outliers.floor_dph / batch.outliers.floor_dph, 1.0, 0.01);
  EXPECT_GT(batch.outliers.removed, 40u);
  EXPECT_EQ(stream.outliers.times_s, batch.outliers.times_s);
  EXPECT_NEAR(stream.outliers.scale_dph / batch.outliers.scale_dph, 1.0, 0.05);
  expect_same_series(stream, batch, 1e-12);
}

TEST(Streaming, BurstyRecordIsAveragedBurstByBurstLikeInMemory) {
  // A logger of 5 s at 50 Hz every 305 s (the PAN log's pattern), 40 bursts.
  ScratchDir dir;
  std::ofstream out(dir / "bursts.csv");
  out << "time_s,temp_c,gyro_dph\n";
  for (int b = 0; b < 40; ++b)
    for (int k = 0; k < 250; ++k) {
      const double t = 305.0 * b + 0.02 * k;
      out << fmt::format("{:.2f},{:.4f},{:.5f}\n", t, 20.0 + 0.001 * t, 3.0 + 0.01 * std::sin(7.0 * k + b));
    }
  out.close();
  const PreparedData batch = prepare_data(dir / "bursts.csv", PipelineOptions{});
  const PreparedData stream = prepare_data_streaming(dir / "bursts.csv", PipelineOptions{});
  ASSERT_TRUE(batch.averaging.bursts);
  EXPECT_TRUE(stream.averaging.bursts);
  EXPECT_EQ(stream.averaging.median_spacing_s, batch.averaging.median_spacing_s);
  EXPECT_EQ(stream.series.window_s, batch.series.window_s);
  EXPECT_EQ(stream.series.size(), 40u);
  expect_same_series(stream, batch, 0.0);
}

TEST(Streaming, BadRowDeepInTheFileNamesItsLineAndKeepsNothing) {
  // The error is raised on the reading thread, after many batches have been
  // handed over, and reaches the caller with the file and line.
  ScratchDir dir;
  std::ofstream out(dir / "bad.csv");
  out << "time_s,temp_c,gyro_dph\n";
  for (int k = 0; k < 50000; ++k) out << k << ",20," << (k == 40000 ? "x" : "1.5") << "\n";
  out.close();
  try {
    prepare_data_streaming(dir / "bad.csv", PipelineOptions{});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:40002: column gyro_dph: 'x' is not a number"),
              std::string::npos)
        << e.what();
  }
}

TEST(Streaming, ErrorOfThePreparerStopsTheReader) {
  // A window shorter than the sample interval fails when the prefix is full,
  // while the reading thread still has rows to hand over: it is stopped and
  // joined, and the caller gets the error.
  ScratchDir dir;
  std::ofstream out(dir / "long.csv");
  out << "time_s,temp_c,gyro_dph\n";
  for (std::size_t k = 0; k < kPrefixRows + 20 * kBatchRows; ++k) out << 10 * k << ",20,1.5\n";
  out.close();
  PipelineOptions o;
  o.averaging.window_s = 5.0;
  try {
    prepare_data_streaming(dir / "long.csv", o);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("long.csv"), std::string::npos) << e.what();
  }
}

TEST(Streaming, OnlyLargeFilesWithoutLogColumnsAreStreamed) {
  ScratchDir dir;
  simulate_to(dir / "r.csv", 0.0, 2.0);
  EXPECT_FALSE(streams(dir / "r.csv", PipelineOptions{}));
  bool streamed = true;
  prepare_csv(dir / "r.csv", PipelineOptions{}, &streamed);
  EXPECT_FALSE(streamed);
}

}  // namespace
}  // namespace gyrotherm::fit
