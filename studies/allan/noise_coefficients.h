#pragma once
// A gyro's noise coefficients read from its Allan deviation (IEEE Std
// 952-1997 Annex C; El-Sheimy, Hou & Niu 2008):
//
//   σ²(τ) = 3Q²/τ² + N²/τ + (2 ln 2/π)·B² + K²τ/3
//
// Angle random walk N (°/√h, the −½ line's value at τ = 1 h), rate random
// walk K (°/h/√h, the +½ line's value at τ = 3 h) and quantisation Q (″, the
// −1 line) come from one weighted fit of this curve to σ² at every τ, the
// four squared coefficients non-negative (the best of the sub-models with
// every coefficient ≥ 0). The estimates at different τ are χ² with the
// row's edf (variance 2σ⁴/edf, at the fitted curve: iterated) and
// correlated (they share data; the correlation of octave neighbours is
// taken as √(τ_short/τ_long)); the coefficients' covariance is the
// generalised least-squares one, scaled up by the fit's χ²/dof where the four
// terms do not describe the curve (a Gauss–Markov hump, thermal drift), so
// the intervals carry the fit's uncertainty, not one point's. A coefficient
// is shown only where the fit supports it (its square above zero at 95 %);
// otherwise the report gives its 95 % upper bound. ARW and quantisation are
// then fitted again on the τ where the first fit says white noise makes at
// least 80 % of σ² (a real flicker floor rolls off below its shortest
// correlation time, where a flat B term would pull N down). Measured: with a
// flicker floor a fifth of the white at 1 s, N within 1 % and its 95 %
// interval covering in 100 of 100 records; where flicker exceeds the white
// already at 4 s, N is 26 % low and no interval covers (the white shows at
// two τ only).
//
// Bias instability B (°/h) is read from the flat part of the curve wherever
// it lies: the longest stretch of τ (at least 8 clusters each) whose local
// slope (least squares over the τ within an octave either side) is within ±0.2, a flicker floor or a Gauss–Markov plateau alike; B =
// the stretch's σ / 0.664 (√(2 ln 2/π)), its interval the best-determined
// τ's. It is shown only if the stretch lies above what the fitted white
// noise gives there (at 95 %); a curve still falling at its longest τ gives
// only a bound (B ≤ its lowest σ / 0.664, the flicker floor lies under every
// point), labelled so.

#include <string>

#include "studies/allan/allan_curve.h"
#include "studies/allan/coefficient_labels.h"

namespace gyrotherm::studies {

// How a coefficient was read: the weighted fit of the standard terms to the
// curve, the curve's flat part, or the series' identified noise model
// (series_noise.h). Bias instability may come from any of the last two.
enum class CoefficientMethod { curve_fit, curve_flat, noise_model };
const char* coefficient_method_name(CoefficientMethod m);  // "curve_fit", "curve_flat", "noise_model"

// Which coefficient: what the words name.
enum class CoefficientKind { arw, bias_instability, rrw, quantization };
// How a coefficient was read, or why it is not shown; coefficient_note()
// words it.
enum class Reading {
  fitted,            // the weighted fit of the standard terms; the term dominates τ_from..τ_to
  too_few_taus,      // no weighted fit could be made
  not_separable,     // the term cannot be fitted beside the others on these τ (no bound)
  below_bound,       // not resolved: below upper_bound, the fit's 95 % bound
  too_few_clusters,  // B: fewer than 3 τ with 8 clusters
  flat_part,         // B: the curve's flat part, τ_from..τ_to (plateau: it falls past it)
  still_falling,     // B: a bound only, the curve still falls at its longest usable τ (tau_read_s)
  no_flat_part,      // B: no flat part above the fitted white noise; bound at the lowest point (tau_read_s)
  noise_model,       // B: the series' noise model's flicker floor
  unexplained_flat,  // B: a bound only, a flat part that no noise model names
};

struct NoiseCoefficient {
  CoefficientKind kind = CoefficientKind::arw;
  Reading reading = Reading::too_few_taus;
  bool shown = false;
  CoefficientMethod method = CoefficientMethod::curve_fit;
  double value = 0.0, lo = 0.0, hi = 0.0;   // in the coefficient's unit, at the curve's confidence
  double upper_bound = 0.0;                 // 95 % bound when not shown (0: none)
  double tau_from_s = 0.0, tau_to_s = 0.0;  // the τ range where the term shows
  double tau_read_s = 0.0;                  // where it weighs most (B: where it was read)
  bool plateau = false;                     // B: the curve falls past its flat part beyond its interval (a plateau)
  int fit_taus = 0;                         // fitted, below_bound: the weighted fit's τ and its χ²/dof
  double fit_chi2_per_dof = 0.0;
  double gauss_markov_tau_s = 0.0;          // B: > 0 where the series' noise model has a Gauss–Markov process
  bool flicker_dominates = false;           // noise_model: flicker makes most of the variance there (else weighs most)
  bool has_noise_model = false;             // unexplained_flat: a noise model was identified (and names nothing)
};

// How it was read, or why it is not shown, in words: "weighted fit of the
// standard terms to σ² at 12 τ (χ²/dof 1.1); angle random walk (−½ slope)
// dominates τ = 1–64 s" (the numbers in the units of `labels`, k as read).
std::string coefficient_note(const NoiseCoefficient& k,
                             const CoefficientLabels& labels = coefficient_labels(fit::sensor_kind("gyro")));

struct NoiseCoefficients {
  NoiseCoefficient arw_dpsh;             // °/√h
  NoiseCoefficient bias_instability_dph;  // °/h
  NoiseCoefficient rrw_dph_per_sqrt_h;    // °/h/√h
  NoiseCoefficient quantization_arcsec;   // ″
  double fit_chi2_per_dof = 0.0;          // of the weighted fit (≈ 1 when the terms describe the curve)
};

// 0.664: σ at the flat part of flicker rate noise is √(2 ln 2/π) B.
inline constexpr double kFlickerFloor = 0.6642824702679600;

NoiseCoefficients read_noise_coefficients(const AllanCurve& curve);

// σ²'s bound factor at `edf` degrees of freedom: σ²·edf/χ²_edf(p) (p = 0.025:
// its 95 % upper value).
double chi2_bound(double edf, double p);

}  // namespace gyrotherm::studies
