// Tests for fit/data/averaging.h. Every expected mean, window and gap is worked out
// by hand from the listed samples.

#include "fit/data/averaging.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sim/util/input_error.h"

namespace gyrotherm::fit {
namespace {

// Samples at the given times with temp = 20 + t/10 and gyro = t².
Measurement record(const std::vector<double>& time_s, bool with_temp2 = false) {
  Measurement m;
  m.file = "record.csv";
  m.time_s = time_s;
  for (double t : time_s) {
    m.temp_c.push_back(20.0 + t / 10.0);
    m.gyro_dph.push_back(t * t);
    if (with_temp2) m.temp2_c.push_back(-t);
  }
  return m;
}

std::vector<double> range(double first, double last, double step = 1.0) {
  std::vector<double> out;
  for (double t = first; t <= last + 1e-9; t += step) out.push_back(t);
  return out;
}

std::vector<unsigned char> all_valid(const Measurement& m) {
  return std::vector<unsigned char>(m.size(), 1);
}

std::string error_of(const Measurement& m, const std::vector<unsigned char>& valid,
                     const AveragingOptions& options) {
  try {
    average_windows(m, valid, options);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return {};
}

TEST(AverageWindows, ExactMeansAndThePartialLastWindowIsDropped) {
  // t = 0 … 11, W = 5: [0,5) and [5,10) are full, [10,15) has 2 < 0.5 · 5 samples.
  const Measurement m = record(range(0, 11));
  AveragingReport report;
  const AveragedSeries s = average_windows(m, all_valid(m), {.window_s = 5.0}, &report);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s.time_s[0], 2.0);  // (0+1+2+3+4)/5
  EXPECT_DOUBLE_EQ(s.time_s[1], 7.0);  // (5+…+9)/5
  EXPECT_DOUBLE_EQ(s.temp_c[0], 20.2);
  EXPECT_DOUBLE_EQ(s.temp_c[1], 20.7);
  EXPECT_DOUBLE_EQ(s.gyro_dph[0], 6.0);   // (0+1+4+9+16)/5
  EXPECT_DOUBLE_EQ(s.gyro_dph[1], 51.0);  // (25+36+49+64+81)/5
  EXPECT_EQ(s.samples, (std::vector<std::size_t>{5, 5}));
  EXPECT_EQ(s.run, (std::vector<std::size_t>{0, 0}));
  EXPECT_TRUE(s.temp2_c.empty());
  EXPECT_EQ(s.start_time_s, 0.0);
  EXPECT_EQ(report.dropped_windows, 1u);
  EXPECT_TRUE(report.gaps.empty());
  EXPECT_EQ(report.sample_interval_s, 1.0);
}

TEST(AverageWindows, InvalidSamplesAreExcluded) {
  Measurement m = record(range(0, 9));
  m.gyro_dph[2] = 1000.0;
  std::vector<unsigned char> valid = all_valid(m);
  valid[2] = 0;
  const AveragedSeries s = average_windows(m, valid, {.window_s = 5.0});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s.gyro_dph[0], 6.5);  // (0+1+9+16)/4
  EXPECT_DOUBLE_EQ(s.time_s[0], 2.0);    // (0+1+3+4)/4
  EXPECT_DOUBLE_EQ(s.temp_c[0], 20.2);
  EXPECT_EQ(s.samples, (std::vector<std::size_t>{4, 5}));
}

TEST(AverageWindows, WindowsWithTooFewValidSamplesAreDropped) {
  const Measurement m = record(range(0, 9));
  std::vector<unsigned char> valid = all_valid(m);
  valid[1] = 0;  // window [0,5) keeps 4 of 5
  AveragingReport report;
  AveragedSeries s = average_windows(m, valid, {.window_s = 5.0, .min_fill = 1.0}, &report);
  ASSERT_EQ(s.size(), 1u);  // 4 < 1.0 · 5
  EXPECT_DOUBLE_EQ(s.time_s[0], 7.0);
  EXPECT_EQ(report.dropped_windows, 1u);

  s = average_windows(m, valid, {.window_s = 5.0, .min_fill = 0.8}, &report);
  ASSERT_EQ(s.size(), 2u);                      // 4 ≥ 0.8 · 5
  EXPECT_DOUBLE_EQ(s.gyro_dph[0], 29.0 / 4.0);  // (0+4+9+16)/4
  EXPECT_EQ(report.dropped_windows, 0u);

  // A window of nothing but rejected samples is dropped too.
  std::fill(valid.begin() + 5, valid.end(), 0);
  s = average_windows(m, valid, {.window_s = 5.0, .min_fill = 0.8}, &report);
  EXPECT_EQ(s.size(), 1u);
  EXPECT_EQ(report.dropped_windows, 1u);
}

TEST(AverageWindows, AGapEndsARunAndWindowsRestartAfterIt) {
  // t = 0 … 6, then 10.5 … 21.5 (a 3.5 s step > 3 · 1 s). Run 0: [0,5) kept,
  // [5,10) = {5,6} dropped. Run 1 from 10.5: [10.5,15.5) and [15.5,20.5) kept,
  // [20.5,25.5) = {20.5,21.5} dropped.
  std::vector<double> t = range(0, 6);
  for (double u : range(10.5, 21.5)) t.push_back(u);
  const Measurement m = record(t);
  AveragingReport report;
  const AveragedSeries s = average_windows(m, all_valid(m), {.window_s = 5.0}, &report);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_DOUBLE_EQ(s.time_s[0], 2.0);
  EXPECT_DOUBLE_EQ(s.time_s[1], 12.5);  // (10.5+…+14.5)/5
  EXPECT_DOUBLE_EQ(s.time_s[2], 17.5);
  EXPECT_DOUBLE_EQ(s.gyro_dph[1],
                   (10.5 * 10.5 + 11.5 * 11.5 + 12.5 * 12.5 + 13.5 * 13.5 + 14.5 * 14.5) / 5);
  EXPECT_EQ(s.run, (std::vector<std::size_t>{0, 1, 1}));
  EXPECT_EQ(s.samples, (std::vector<std::size_t>{5, 5, 5}));
  ASSERT_EQ(report.gaps.size(), 1u);
  EXPECT_EQ(report.gaps[0].from_s, 6.0);
  EXPECT_EQ(report.gaps[0].to_s, 10.5);
  EXPECT_EQ(report.dropped_windows, 2u);
  EXPECT_EQ(report.sample_interval_s, 1.0);  // steps: eighteen 1 s, one 3.5 s
}

TEST(AverageWindows, NoWindowSpansAGapEvenWhenAligned) {
  // t = 0 … 9 and 20 … 29: the windows [0,5) [5,10) [20,25) [25,30); a window
  // spanning the gap would mix samples of both runs.
  std::vector<double> t = range(0, 9);
  for (double u : range(20, 29)) t.push_back(u);
  const Measurement m = record(t, true);
  AveragingReport report;
  const AveragedSeries s = average_windows(m, all_valid(m), {.window_s = 5.0}, &report);
  EXPECT_EQ(s.time_s, (std::vector<double>{2.0, 7.0, 22.0, 27.0}));
  EXPECT_EQ(s.temp2_c, (std::vector<double>{-2.0, -7.0, -22.0, -27.0}));
  EXPECT_EQ(s.run, (std::vector<std::size_t>{0, 0, 1, 1}));
  ASSERT_EQ(report.gaps.size(), 1u);
  EXPECT_EQ(report.gaps[0].from_s, 9.0);
  EXPECT_EQ(report.gaps[0].to_s, 20.0);
  EXPECT_EQ(report.dropped_windows, 0u);
}

TEST(AverageWindows, AStepLongerThanTheWindowIsAGap) {
  // Steps of 1 s and one of 2.5 s: under 3 · 1 s but over W = 2 s.
  std::vector<double> t = range(0, 9);
  for (double u : range(11.5, 15.5)) t.push_back(u);
  const Measurement m = record(t);
  AveragingReport report;
  const AveragedSeries s = average_windows(m, all_valid(m), {.window_s = 2.0}, &report);
  ASSERT_EQ(report.gaps.size(), 1u);
  EXPECT_EQ(report.gaps[0].from_s, 9.0);
  EXPECT_EQ(report.gaps[0].to_s, 11.5);
  // Run 0: [0,2) … [8,10), five windows; run 1: [11.5,13.5) [13.5,15.5), and
  // {15.5} alone in [15.5,17.5) is 1 sample, kept (≥ 0.5 · 2).
  EXPECT_EQ(s.time_s, (std::vector<double>{0.5, 2.5, 4.5, 6.5, 8.5, 12.0, 14.0, 15.5}));
  EXPECT_EQ(s.run, (std::vector<std::size_t>{0, 0, 0, 0, 0, 1, 1, 1}));
}

TEST(AverageWindows, IrregularSampling) {
  // Steps 0.8 1.3 0.9 0.9 1.3 0.8 1.1 0.9 0.8 1.3 0.9 → median 0.9 s; W = 5 s
  // needs 0.5 · 5/0.9 = 2.8 valid samples. [0,5): 0 0.8 2.1 3.0 3.9;
  // [5,10): 5.2 6.0 7.1 8.0 8.8; [10,15): 10.1 11.0 → dropped.
  const Measurement m = record({0, 0.8, 2.1, 3.0, 3.9, 5.2, 6.0, 7.1, 8.0, 8.8, 10.1, 11.0});
  AveragingReport report;
  const AveragedSeries s = average_windows(m, all_valid(m), {.window_s = 5.0}, &report);
  EXPECT_NEAR(report.sample_interval_s, 0.9, 1e-12);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_NEAR(s.time_s[0], 9.8 / 5, 1e-12);
  EXPECT_NEAR(s.time_s[1], 35.1 / 5, 1e-12);
  EXPECT_NEAR(s.gyro_dph[0], (0.64 + 4.41 + 9.0 + 15.21) / 5, 1e-12);
  EXPECT_NEAR(s.gyro_dph[1], (27.04 + 36.0 + 50.41 + 64.0 + 77.44) / 5, 1e-12);
  EXPECT_EQ(report.dropped_windows, 1u);
  EXPECT_TRUE(report.gaps.empty());
}

TEST(AverageWindows, EpochTimesKeepTheirDigits) {
  // Unix times at 4 Hz: 1.7e9 + k/4 is exact in a double, and so is the mean
  // of each window, 1.7e9 + 49.875 and 1.7e9 + 149.875; a sum of 400 absolute
  // times (6.8e11) would round off in the 5th decimal.
  std::vector<double> t;
  for (int k = 0; k < 900; ++k) t.push_back(1.7e9 + 0.25 * k);
  const Measurement m = record(t);
  const AveragedSeries s = average_windows(m, all_valid(m), {.window_s = 100.0});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s.time_s[0], 1.7e9 + 49.875);
  EXPECT_EQ(s.time_s[1], 1.7e9 + 149.875);
  EXPECT_EQ(s.start_time_s, 1.7e9);
}

TEST(AverageWindows, NoSurvivingWindowSaysHowLongTheRecordIs) {
  const Measurement m = record(range(0, 29));
  const std::string message = error_of(m, all_valid(m), {.window_s = 100.0});
  for (const char* fragment : {"record.csv", "29 s long", "100 s", "--avg"})
    EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " not in: " << message;
}

TEST(AverageWindows, TheNoWindowMessageShowsNumbersForPeople) {
  // 0.1 s steps summed up: the last time is 29.300000000000068, said as 29.3.
  std::vector<double> t;
  for (double u = 0.0; u < 29.35; u += 0.1) t.push_back(u);
  const Measurement m = record(t);
  const std::string message = error_of(m, all_valid(m), {.window_s = 100.0});
  EXPECT_NE(message.find("29.3 s long"), std::string::npos) << message;
  EXPECT_EQ(message.find("00000"), std::string::npos) << message;
}

TEST(AverageWindows, AWindowShorterThanTheSampleIntervalIsRejected) {
  const Measurement m = record(range(0, 100, 10));
  const std::string message = error_of(m, all_valid(m), {.window_s = 5.0});
  EXPECT_NE(message.find("--avg 5"), std::string::npos) << message;
  EXPECT_NE(message.find("sample interval (10 s)"), std::string::npos) << message;
}

TEST(AverageWindows, BadOptionsAreRejectedByName) {
  const Measurement m = record(range(0, 9));
  const std::vector<unsigned char> valid = all_valid(m);
  for (double w : {0.0, -100.0, std::nan("")})
    EXPECT_NE(error_of(m, valid, {.window_s = w}).find("--avg"), std::string::npos);
  for (double g : {1.0, 0.5})
    EXPECT_NE(error_of(m, valid, {.gap_factor = g}).find("gap_factor"), std::string::npos);
  for (double f : {0.0, -0.1, 1.5})
    EXPECT_NE(error_of(m, valid, {.min_fill = f}).find("min_fill"), std::string::npos);
  EXPECT_NO_THROW(AveragingOptions{}.validate());
}

// A logger that records in bursts: 5 s at 10 Hz every 300 s, shorter than
// the 100 s window; each burst becomes one window, its mean at its centre.
TEST(AverageWindows, BurstsShorterThanTheWindowAreOneWindowEach) {
  std::vector<double> t;
  for (int b = 0; b < 6; ++b)
    for (const double u : range(0.0, 4.9, 0.1)) t.push_back(300.0 * b + u);
  const Measurement m = record(t);
  AveragingReport report;
  const AveragedSeries s = average_windows(m, all_valid(m), AveragingOptions{}, &report);
  ASSERT_EQ(s.size(), 6u);
  EXPECT_TRUE(report.bursts);
  EXPECT_EQ(report.gaps.size(), 5u);
  EXPECT_NEAR(report.median_run_s, 5.0, 1e-9);
  EXPECT_NEAR(report.median_spacing_s, 300.0, 1e-9);
  EXPECT_NEAR(s.window_s, 5.0, 1e-9);
  for (std::size_t b = 0; b < 6; ++b) {
    const double centre = 300.0 * static_cast<double>(b) + 2.45;
    EXPECT_NEAR(s.time_s[b], centre, 1e-9);
    EXPECT_NEAR(s.temp_c[b], 20.0 + centre / 10.0, 1e-9);
    EXPECT_EQ(s.samples[b], 50u);
    EXPECT_EQ(s.run[b], b);
  }
  // A burst mostly made of rejected samples is dropped, as a window would be.
  std::vector<unsigned char> valid = all_valid(m);
  for (std::size_t k = 50; k < 80; ++k) valid[k] = 0;
  EXPECT_EQ(average_windows(m, valid, AveragingOptions{}).size(), 5u);
  // A window shorter than the bursts: plain windows again.
  AveragingOptions short_windows;
  short_windows.window_s = 1.0;
  AveragingReport plain;
  EXPECT_EQ(average_windows(m, all_valid(m), short_windows, &plain).size(), 6u * 5u);
  EXPECT_FALSE(plain.bursts);
}

// A continuous record with one short fragment is not bursty: the fragment's
// partial window is dropped as before.
TEST(AverageWindows, AShortRunInAContinuousRecordIsNotABurst) {
  std::vector<double> t = range(0.0, 999.0);
  for (const double u : range(1500.0, 1530.0)) t.push_back(u);
  for (const double u : range(2000.0, 2999.0)) t.push_back(u);
  const Measurement m = record(t);
  AveragingReport report;
  const AveragedSeries s = average_windows(m, all_valid(m), AveragingOptions{}, &report);
  EXPECT_FALSE(report.bursts);
  EXPECT_EQ(s.size(), 20u);
  EXPECT_EQ(s.window_s, 100.0);
}

TEST(WindowAverager, StreamsOneSampleAtATime) {
  // The same windows as ExactMeans, fed by hand with one rejected sample.
  WindowAverager averager({.window_s = 5.0}, 1.0, true);
  for (int k = 0; k <= 11; ++k) {
    const double t = k;
    averager.add(t, 20.0 + t, k == 7 ? 1e6 : 2.0 * t, 30.0 - t, k != 7);
  }
  const AveragedSeries s = averager.finish();
  EXPECT_EQ(s.time_s, (std::vector<double>{2.0, 7.0}));  // (5+6+8+9)/4 = 28/4
  EXPECT_EQ(s.temp_c, (std::vector<double>{22.0, 27.0}));
  EXPECT_EQ(s.gyro_dph, (std::vector<double>{4.0, 14.0}));  // 2 · 28/4, not the 1e6
  EXPECT_EQ(s.temp2_c, (std::vector<double>{28.0, 23.0}));
  EXPECT_EQ(s.samples, (std::vector<std::size_t>{5, 4}));
  EXPECT_EQ(averager.report().dropped_windows, 1u);
  EXPECT_EQ(averager.record_s(), 11.0);
  EXPECT_EQ(averager.longest_run_s(), 11.0);
}

}  // namespace
}  // namespace gyrotherm::fit
