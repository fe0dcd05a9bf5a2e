// The window mean of a rate from the samples at the window's edges
// (fit/data/edge_rate.h): exact on a ramp, right across a ramp's corner where
// the difference of window means is not, an honest standard error, and dT's
// coefficient unbiased on a profile of sharp corners.

#include "fit/data/edge_rate.h"

#include <gtest/gtest.h>

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <vector>

#include "fit/data/prepare.h"
#include "fit/model/formula.h"
#include "fit/pipeline.h"

namespace gyrotherm::fit {
namespace {

TEST(EdgeRate, ExactOnARamp) {
  EdgeRate e(10, 1.0);
  for (int i = 0; i < 100; ++i) e.add(i, 3.0 + 0.0125 * i);
  EXPECT_NEAR(e.rate(), 0.0125, 1e-12);
  EXPECT_NEAR(e.standard_error(), 0.0, 1e-12);  // no noise
  EdgeRate few(10, 1.0);
  for (int i = 0; i < 19; ++i) few.add(i, i);
  EXPECT_TRUE(std::isnan(few.rate()));  // the edges' lines would share samples
}

// A window that holds a ramp's start: the mean rate of its samples is the
// ramp's rate times the share of samples on it.
TEST(EdgeRate, TheMeanRateAcrossARampsCorner) {
  const double rate = 5.0 / 60.0;  // 5 °C/min
  EdgeRate e(10, 1.0);
  double mean_rate = 0.0;
  for (int i = 0; i < 100; ++i) {
    const double t = i;
    e.add(t, 20.0 + rate * std::max(0.0, t - 40.0));
    mean_rate += (t >= 40.0 ? rate : 0.0) / 100.0;
  }
  EXPECT_NEAR(e.rate() / mean_rate, 1.0, 0.02);
}

TEST(EdgeRate, ItsStandardErrorIsTheSpreadOfTheRateUnderNoise) {
  boost::random::mt19937_64 rng(5);
  boost::random::normal_distribution<double> normal;
  const double sigma = 0.003;
  double sum = 0.0, sum2 = 0.0, se = 0.0;
  const int windows = 3000;
  for (int w = 0; w < windows; ++w) {
    EdgeRate e(EdgeRate::samples_for(100.0, 1.0), 1.0);
    for (int i = 0; i < 100; ++i) e.add(i, 0.02 * i + sigma * normal(rng));
    sum += e.rate();
    sum2 += e.rate() * e.rate();
    se += e.standard_error() / windows;
  }
  const double mean = sum / windows, sd = std::sqrt(sum2 / windows - mean * mean);
  EXPECT_NEAR(mean, 0.02, 4.0 * sd / std::sqrt(windows));
  EXPECT_GT(se / sd, 0.85);
  EXPECT_LT(se / sd, 1.15);
}

// Holds joined by 5 °C/min ramps, sampled at 1 Hz, the gyro exactly the
// paper's model of the samples' own rate: dT's coefficient from 100 s windows.
TEST(EdgeRate, DtIsUnbiasedOnSharpCorners) {
  Measurement m;
  const double b0 = -7.07712, b1 = -3.05e-4, b2 = 1.06e-6, b3 = 1.81;
  const std::vector<double> levels = {20.0, 60.0, -20.0, 40.0, 0.0, 55.0, 20.0};
  double t = 0.0, temp = levels.front();
  const auto sample = [&](double rate) {
    m.time_s.push_back(t);
    m.temp_c.push_back(temp);
    m.gyro_dph.push_back(b0 + b1 * temp + b2 * temp * temp + b3 * rate);
    t += 1.0;
  };
  for (std::size_t k = 1; k < levels.size(); ++k) {
    for (int i = 0; i < 1830; ++i) sample(0.0);  // a hold (not a whole number of windows)
    const double rate = (levels[k] > temp ? 5.0 : -5.0) / 60.0;
    while (std::abs(levels[k] - temp) > 1e-9) {
      const double step = std::abs(levels[k] - temp) < std::abs(rate) ? levels[k] - temp : rate;
      sample(step);  // the rate over the next second, as the window mean of the output sees it
      temp += step;
    }
  }
  for (int i = 0; i < 1830; ++i) sample(0.0);
  PipelineOptions quiet;
  quiet.remove_outliers = false;
  const PreparedData data = prepare_data(m, quiet);
  const ModelFit f = fit_model(data, parse_formula("T + T^2 + dT"), find_engine("ols"), {});
  EXPECT_NEAR(f.coefficients.b[2] / b3, 1.0, 0.002) << f.coefficients.b[2];
}

}  // namespace
}  // namespace gyrotherm::fit
