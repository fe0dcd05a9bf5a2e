#pragma once
// The Allan variance of Gauss–Markov processes, the one formula the simulator
// (sim/noise.h: flicker as a bank of them, scaled to its peak) and the
// fitter's noise model (fit/model/noise_model.h: the bank's floor, a model's
// curve) both use.
//
// A unit-variance process with correlation time T has, at averaging time τ
// (x = τ/T), the Allan variance
//     g(x) = (2x − 3 + 4e^{−x} − e^{−2x}) / x²
// (IEEE Std 952-1997, annex C); it behaves like 2x/3 as x → 0 and peaks at
// x ≈ 1.89.

#include <span>

namespace gyrotherm {

// g(x) for x > 0, to full precision at small x (the closed form loses digits
// to cancellation there; its Taylor series is summed instead).
double gauss_markov_allan_shape(double x);

// The largest Σ_i g(τ/τ_i) of a bank of unit-variance processes (correlation
// times `taus`) over τ log-spaced from `from_s` to `to_s` in `steps` steps
// (from_s alone when steps is 0): the bank's Allan variance at its peak.
double bank_allan_peak(std::span<const double> taus, double from_s, double to_s, int steps);

}  // namespace gyrotherm
