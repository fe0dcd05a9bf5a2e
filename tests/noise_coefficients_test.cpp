// studies/allan/noise_coefficients.h on curves made by hand, where the answer
// is known from the shape alone.

#include "studies/allan/noise_coefficients.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gyrotherm::studies {
namespace {

// White rate noise and a rate random walk, σ²(τ) = 1/τ + τ/65536 ((°/h)²,
// τ0 = 1 s, 2^16 samples): a V whose bottom, τ = 256 s, is the only τ where
// the local slope is within ±0.2 (±0.27 an octave either side).
AllanCurve v_shaped_curve() {
  AllanCurve c;
  c.name = "raw";
  c.tau0_s = 1.0;
  c.samples = std::size_t{1} << 16;
  c.runs = 1;
  c.span_s = static_cast<double>(c.samples - 1);
  c.longest_run_s = c.span_s;
  for (std::size_t m = 1; m <= 4096; m *= 2) {
    AllanRow r;
    r.m = m;
    r.tau_s = static_cast<double>(m);
    r.adev_dph = std::sqrt(1.0 / r.tau_s + r.tau_s / 65536.0);
    r.edf = static_cast<double>(c.samples) / static_cast<double>(m);
    r.lo_dph = r.adev_dph * (1.0 - 1.0 / std::sqrt(r.edf));
    r.hi_dph = r.adev_dph * (1.0 + 1.0 / std::sqrt(r.edf));
    r.terms = c.samples - 2 * m;
    c.rows.push_back(r);
  }
  return c;
}

// A flat stretch that is a single τ is named as that τ, not as "256–256 s".
TEST(NoiseCoefficients, AFlatStretchOfOneTauIsNamedAsThatTau) {
  const NoiseCoefficient b = read_noise_coefficients(v_shaped_curve()).bias_instability_dph;
  ASSERT_TRUE(b.shown) << coefficient_note(b);
  EXPECT_EQ(b.tau_from_s, 256.0);
  EXPECT_EQ(b.tau_to_s, 256.0);
  EXPECT_NE(coefficient_note(b).find("τ = 256 s"), std::string::npos) << coefficient_note(b);
  EXPECT_EQ(coefficient_note(b).find("256–256"), std::string::npos) << coefficient_note(b);
}

}  // namespace
}  // namespace gyrotherm::studies
