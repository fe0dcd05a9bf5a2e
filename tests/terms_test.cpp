// Regressors against values computed by hand.

#include "fit/model/terms.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fit/model/formula.h"
#include "sim/util/input_error.h"

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

TEST(Terms, CentralDifferencesAreExactForAQuadraticInsideARun) {
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
  EXPECT_NEAR(d.grad_c[0], (2.5 + 0.5) - (2.0 + 0.5 + 1e-6 * 2500), 1e-12);
  EXPECT_NEAR(d.time_h[8], 1450.0 / 3600.0, 1e-15);
}

TEST(Terms, CausalDifferencesUseOnlyThePast) {
  const DerivedSeries d = derive(quadratic_in_time(), DerivativeMode::causal);
  EXPECT_EQ(d.rate_c_per_s[0], 0.0);  // nothing before the first window
  EXPECT_NEAR(d.rate_c_per_s[2], (d.temp_c[2] - d.temp_c[1]) / 100.0, 1e-15);
  EXPECT_EQ(d.rate_c_per_s[6], 0.0);  // first window after the gap
  EXPECT_NEAR(d.rate_c_per_s[7], (d.temp_c[7] - d.temp_c[6]) / 100.0, 1e-15);
}

TEST(Terms, RegressorsByHand) {
  const DerivedSeries d = derive(quadratic_in_time(), DerivativeMode::central);
  std::vector<double> out(d.size());
  auto reg = [&](const char* name, double parameter = 0.0) {
    find_term(name)->regressor(d, parameter, out);
    return out;
  };
  EXPECT_NEAR(reg("T^3")[1], std::pow(d.temp_c[1], 3), 1e-12);
  EXPECT_NEAR(reg("T*dT")[1], d.temp_c[1] * d.rate_c_per_s[1], 1e-15);
  EXPECT_NEAR(reg("warmup", 1800.0)[6], std::exp(-1250.0 / 1800.0), 1e-15);
  EXPECT_NEAR(reg("t")[8], 1450.0 / 3600.0, 1e-15);
  // hyst: every rate here is ≈ 0.01 °C/s, heating.
  EXPECT_EQ(reg("hyst", 1e-3)[2], 1.0);
  EXPECT_EQ(reg("hyst", 0.5)[2], 0.0);
}

TEST(Terms, RegistryHasTheDesignContract) {
  EXPECT_EQ(term_list(), "T, T^2, T^3, dT, T*dT, d2T, grad, hyst, warmup, t");
  EXPECT_TRUE(find_term("grad")->needs_temp2);
  EXPECT_TRUE(find_term("warmup")->parameter.has_value());
  EXPECT_TRUE(find_term("hyst")->parameter.has_value());
  EXPECT_EQ(find_term("bogus"), nullptr);
}

TEST(Formula, ParsesTheDefaultAndRejectsBadFormulas) {
  const auto terms = parse_formula(" T+T^2 + dT ");
  ASSERT_EQ(terms.size(), 3u);
  EXPECT_EQ(formula_text(terms), "T + T^2 + dT");
  EXPECT_EQ(formula_text(parse_formula("1 + grad")), "grad");
  auto message = [](const char* f) {
    try {
      parse_formula(f);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("T + T^4").find("unknown term 'T^4' (known terms: T, T^2"), std::string::npos);
  EXPECT_NE(message("T + T").find("'T' appears twice"), std::string::npos);
  EXPECT_NE(message("").find("empty"), std::string::npos);
  EXPECT_NE(message("T ++ dT").find("empty term"), std::string::npos);
  EXPECT_NE(message("1").find("no terms"), std::string::npos);
}

}  // namespace
}  // namespace gyrotherm::fit
