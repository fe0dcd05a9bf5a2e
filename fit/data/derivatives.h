#pragma once
// The per-window quantities every regressor is built from (fit/model/terms.h):
// time since the first sample, the window means of temp_c (and temp2_c), and
// their first and second time derivatives.
//
// Derivatives are taken on the averaged series within each gap-free run:
// central differences (the default; one-sided at the ends of a run), or
// backward differences for a causal, real-time compensator (0 at the first
// window of a run).

#include <cstddef>
#include <vector>

#include "fit/data/averaging.h"

namespace gyrotherm::fit {

enum class DerivativeMode { central, causal };

struct DerivedSeries {
  std::vector<double> time_h;    // hours since the first sample
  std::vector<double> temp_c;
  std::vector<double> rate_c_per_s;
  std::vector<double> accel_c_per_s2;
  std::vector<double> grad_c;    // temp2 − temp (empty without temp2)
  std::size_t size() const { return temp_c.size(); }
};

DerivedSeries derive(const AveragedSeries& data, DerivativeMode mode);

}  // namespace gyrotherm::fit
