#pragma once
// Equivalent degrees of freedom of the overlapping Allan variance for
// power-law noise S_y(f) ∝ f^α, by Greenhall's algorithm:
//
//   C. A. Greenhall and W. J. Riley, "Uncertainty of stability variances
//   based on finite differences", Proc. 35th PTTI Meeting (2003), §3–4:
//   eq. (7) the generalised autocovariance sw(t) of the phase for each α,
//   (8) its filtering by the m-average, (9) the second difference, (10) the
//   basic sum over the estimator's overlapping terms, and Tables 2–3 for the
//   large-sample limit (1/edf = (a0 − a1/r)/r, r = M/m).
//
// For the overlapping Allan variance (d = 2, the unmodified filter F = m,
// the stride S = m) on N phase points (N − 1 rates) at averaging factor m,
// with M = N − 2m terms (N phase points): the basic sum term by term while it
// has at most 100 terms, the tables beyond.
//
// One choice differs from the paper's case 2.1a (which filters the phase
// over τ0, F = m, for small m): a gyro's samples are averages of the rate
// over τ0, so the angle at the sample times is the exact integral and needs
// no filter; for α ≤ 0 the unfiltered limit F = ∞ is used at every m. It
// gives the exact discrete edf for white rate noise (2M/3 at m = 1: 682 on
// 1025 points, where F = m gives 801). White angle noise (α = 2) with r = M/m ≤ 2
// (up to about four τ of data) falls back to NIST SP 1065 Table 5, as the paper
// leaves that case to a direct sum.
//
// Tested against NIST SP 1065 Table 5 (which approximates the same
// quantity) and by the coverage of the intervals over many seeds.

#include <cstddef>

namespace gyrotherm::studies {

// α ∈ {2, 1, 0, −1, −2}; n_phase = samples + 1; 2m ≤ n_phase − 1. Returns at least 1.
double greenhall_edf(int alpha, std::size_t m, std::size_t n_phase);

// NIST SP 1065 Table 5's approximation of the same (kept for comparison).
double table5_edf(int alpha, double n_phase, double m);

}  // namespace gyrotherm::studies
