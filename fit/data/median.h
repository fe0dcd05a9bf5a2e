#pragma once
// The median of a sample, the one definition every robust rule of the data
// pipeline uses: the middle value of an odd count, the mean of the two middle
// values of an even count, NaN for no values (a median of nothing is not a
// number; every caller checks for that case first). O(n) by selection
// (std::nth_element), reordering the values given.

#include <algorithm>
#include <limits>
#include <span>
#include <vector>

namespace gyrotherm::fit {

inline double median_in_place(std::span<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  if (v.size() % 2 == 1) return *middle;
  return 0.5 * (*std::max_element(v.begin(), middle) + *middle);
}

inline double median_of(std::vector<double> v) { return median_in_place(v); }

}  // namespace gyrotherm::fit
