#pragma once
// A gyro's noise coefficients read from its Allan deviation the standard way
// (IEEE Std 952-1997 Annex C; El-Sheimy, Hou & Niu 2008):
//
//   σ²(τ) = 3Q²/τ² + N²/τ + (2 ln 2/π)·B² + K²τ/3 + …
//
// each term dominating one region of the log-log curve:
// - angle random walk N (°/√h): the −½ slope region (white rate noise),
//   σ(τ) = N/√τ. Stated with the τ = 1 h convention: N is the value of the
//   −½ line at τ = 1 h, so N[°/√h] = σ[°/h]·√(τ[h]).
// - bias instability B (°/h): the flat part, σ = √(2 ln 2/π)·B ≈ 0.664·B,
//   read at the curve's flat extremum: its minimum between the falling and
//   rising parts; at the longest τ when the curve has flattened there (last
//   slope above −0.2, and the last τ's 95 % lower bound above the −½ line
//   from two τ before) but the record ends before it rises; or, when the
//   curve has no minimum but a hump (a first-order Gauss–Markov bias wanders
//   like that), the hump's top.
// - rate random walk K (°/h/√h): the +½ slope region, σ(τ) = K·√(τ/3), the
//   value of the +½ line at τ = 3 h.
// - quantisation Q (″): the −1 slope region, σ(τ) = √3·Q/τ.
//
// The region of a term is the set of τ whose identified noise type
// (allan_curve.h) is that term's and where the curve's local slope is the
// term's within ±0.1 (next to another region the two mix: a gyro's
// quantisation lifts the shortest τ above the ARW line); the coefficient is
// read at the region's τ with the most degrees of freedom, and its interval
// is that τ's interval scaled the same way. A term whose region the record does not show is
// reported as not shown, with the reason.

#include <string>

#include "studies/allan/allan_curve.h"

namespace gyrotherm::studies {

struct NoiseCoefficient {
  bool shown = false;
  double value = 0.0, lo = 0.0, hi = 0.0;  // in the coefficient's unit
  double tau_from_s = 0.0, tau_to_s = 0.0;  // the region's τ range
  double tau_read_s = 0.0;                  // where it was read
  std::string note;                         // how it was read, or why it is not shown
};

struct NoiseCoefficients {
  NoiseCoefficient arw_dpsh;             // °/√h
  NoiseCoefficient bias_instability_dph;  // °/h
  NoiseCoefficient rrw_dph_per_sqrt_h;    // °/h/√h
  NoiseCoefficient quantization_arcsec;   // ″
};

// 0.664: σ at the flat part of flicker rate noise is √(2 ln 2/π) B.
inline constexpr double kFlickerFloor = 0.6642824702679600;

NoiseCoefficients read_noise_coefficients(const AllanCurve& curve);

}  // namespace gyrotherm::studies
