// The window means' derivatives against values computed by hand.

#include "fit/data/derivatives.h"

#include <gtest/gtest.h>

#include <cmath>


namespace gyrotherm::fit {
namespace {

AveragedSeries quadratic_in_time() {
  // T = 2 + 0.01 t + 1e-6 t², windows every 100 s, two runs split by a gap.
  AveragedSeries s;
  s.start_time_s = 0.0;
  const double times[] = {50, 150, 250, 350, 450, 550, 1250, 1350, 1450};
  const std::size_t runs[] = {0, 0, 0, 0, 0, 0, 1, 1, 1};
  for (int i = 0; i < 9; ++i) {
    const double t = times[i];
    s.time_s.push_back(t);
    s.temp_c.push_back(2.0 + 0.01 * t + 1e-6 * t * t);
    s.temp2_c.push_back(2.5 + 0.01 * t);
    s.gyro_dph.push_back(0.0);
    s.samples.push_back(100);
    s.run.push_back(runs[i]);
  }
  return s;
}

TEST(Derivatives, CentralDifferencesAreExactForAQuadraticInsideARun) {
  const DerivedSeries d = derive(quadratic_in_time(), DerivativeMode::central);
  // Inside a run: dT/dt = 0.01 + 2e-6 t exactly.
  EXPECT_NEAR(d.rate_c_per_s[1], 0.01 + 2e-6 * 150, 1e-15);
  EXPECT_NEAR(d.rate_c_per_s[2], 0.01 + 2e-6 * 250, 1e-15);
  EXPECT_NEAR(d.rate_c_per_s[7], 0.01 + 2e-6 * 1350, 1e-15);
  // Run ends are one-sided, never across the gap (550 → 1250).
  EXPECT_NEAR(d.rate_c_per_s[5], (d.temp_c[5] - d.temp_c[4]) / 100.0, 1e-15);
  EXPECT_NEAR(d.rate_c_per_s[6], (d.temp_c[7] - d.temp_c[6]) / 100.0, 1e-15);
  // Second derivative of the quadratic: 2e-6 where both neighbouring rates
  // are central (windows 2 and 3 of the first run).
  EXPECT_NEAR(d.accel_c_per_s2[2], 2e-6, 1e-15);
  EXPECT_NEAR(d.accel_c_per_s2[3], 2e-6, 1e-15);
  EXPECT_EQ(d.temp2_c[0], 2.5 + 0.5);
  EXPECT_EQ(d.time_s[8], 1450.0);  // since the first sample
  EXPECT_EQ(d.switch_on_s, 0.0);   // a measured gyro is switched on at its first sample
}

TEST(Derivatives, CausalDifferencesUseOnlyThePast) {
  const DerivedSeries d = derive(quadratic_in_time(), DerivativeMode::causal);
  EXPECT_EQ(d.rate_c_per_s[0], 0.0);  // nothing before the first window
  EXPECT_NEAR(d.rate_c_per_s[2], (d.temp_c[2] - d.temp_c[1]) / 100.0, 1e-15);
  EXPECT_EQ(d.rate_c_per_s[6], 0.0);  // first window after the gap
  EXPECT_NEAR(d.rate_c_per_s[7], (d.temp_c[7] - d.temp_c[6]) / 100.0, 1e-15);
}

// Window means 305 s apart across gaps (a bursty logger): the default span
// of 600 s bridges them, so dT/dt is central and exact for a quadratic; a span
// shorter than the spacing leaves every window without neighbours.
TEST(Derivatives, BridgeGapsUpToTheSpan) {
  AveragedSeries s;
  for (int i = 0; i < 6; ++i) {
    const double t = 2.5 + 305.0 * i;
    s.time_s.push_back(t);
    s.temp_c.push_back(24.0 - 1e-3 * t + 1e-8 * t * t);
    s.gyro_dph.push_back(0.0);
    s.samples.push_back(250);
    s.run.push_back(static_cast<std::size_t>(i));  // every window its own run
  }
  const DerivedSeries d = derive(s, DerivativeMode::central);
  for (std::size_t p = 1; p + 1 < s.size(); ++p)
    EXPECT_NEAR(d.rate_c_per_s[p], -1e-3 + 2e-8 * s.time_s[p], 1e-15) << p;
  EXPECT_NEAR(d.accel_c_per_s2[2], 2e-8, 1e-15);
  const DerivedSeries causal = derive(s, DerivativeMode::causal);
  EXPECT_EQ(causal.rate_c_per_s[0], 0.0);
  EXPECT_NEAR(causal.rate_c_per_s[3], (s.temp_c[3] - s.temp_c[2]) / 305.0, 1e-15);
  const DerivedSeries unbridged = derive(s, DerivativeMode::central, 200.0);
  for (double r : unbridged.rate_c_per_s) EXPECT_EQ(r, 0.0);
}

}  // namespace
}  // namespace gyrotherm::fit
