#pragma once
// Numbers several files use, defined once.

#include <limits>

namespace gyrotherm {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The standard normal's 97.5 % quantile: a two-sided 95 % interval is ±kZ95·σ.
inline constexpr double kZ95 = 1.959963984540054;

}  // namespace gyrotherm
