#pragma once
// Numbers written as text fast, with exactly the digits printf and fmt give
// ("%.5f", "{:.10g}"): for the CSV records `simulate` and `compensate` write,
// where formatting was most of the time (results/benchmarks.md).
//
// Fixed notation with d decimals: with r = |v|·10^d computed in floating
// point (10^d exact for d ≤ 22, so r is within half an ulp of the exact
// product R), the correctly rounded integer of R is that of r unless R may
// lie on the other side of a half-integer than r: the fast path takes r's
// rounding only when r's fractional part is further than 2⁻⁵¹·r (a few ulps)
// from ½, and r < 2⁵³; otherwise, and for NaN and infinities, it calls
// std::to_chars, which is exact. The sign of a negative value is kept even
// when it rounds to zero ("-0.00000"), as printf keeps it.
//
// General notation (%.Ng) always goes to std::to_chars (chars_format::general
// with precision N, C's %g rules).

#include <charconv>
#include <cmath>
#include <cstdint>

namespace gyrotherm {

// Writes v with `decimals` decimals (0 ≤ decimals ≤ 17) at p; returns the end.
// p needs room for 350 characters in the worst case (to_chars of a huge value),
// 32 for |v| < 1e12.
inline char* write_fixed(char* p, double v, int decimals) {
  static constexpr double kPow10[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,
                                      1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17};
  const double a = std::fabs(v);
  const double r = a * kPow10[decimals];
  if (std::isfinite(r) && r < 9007199254740992.0) {  // 2⁵³
    const double whole = std::floor(r);
    const double fraction = r - whole;
    if (std::fabs(fraction - 0.5) > 4.5e-16 * r + 1e-300) {
      std::uint64_t n = static_cast<std::uint64_t>(whole) + (fraction > 0.5 ? 1 : 0);
      if (std::signbit(v)) *p++ = '-';
      char digits[24];
      int count = 0;
      do {
        digits[count++] = static_cast<char>('0' + n % 10);
        n /= 10;
      } while (n != 0 || count <= decimals);
      for (int i = count - 1; i >= decimals; --i) *p++ = digits[i];
      if (decimals > 0) {
        *p++ = '.';
        for (int i = decimals - 1; i >= 0; --i) *p++ = digits[i];
      }
      return p;
    }
  }
  return std::to_chars(p, p + 350, v, std::chars_format::fixed, decimals).ptr;
}

// %.{precision}g.
inline char* write_general(char* p, double v, int precision) {
  return std::to_chars(p, p + 350, v, std::chars_format::general, precision).ptr;
}

}  // namespace gyrotherm
