#pragma once
// Numbers in messages, formatted for people: five significant digits, no
// binary noise ("7324.6 s", not "7324.610000000001 s"); a count with its noun
// in the right number ("1 window", "3 windows"); a range with enough decimals
// to tell its ends apart ("13.2..13.6 °C", not "13..14" or "13..13").

#include <fmt/format.h>

#include <cctype>
#include <cmath>

#include <string>
#include <string_view>

namespace gyrotherm {

inline std::string human(double v) { return fmt::format("{:.5g}", v); }

// "1 window", "2 windows"; `plural` for nouns that do not just take an s
// (counted(n, "glitch", "glitches")).
inline std::string counted(std::size_t n, std::string_view singular, std::string_view plural = {}) {
  if (n == 1) return fmt::format("1 {}", singular);
  return plural.empty() ? fmt::format("{} {}s", n, singular) : fmt::format("{} {}", n, plural);
}

// The decimals, at least `at_least` (and at most 6), whose last digit is no
// coarser than |a − b|: a and b print apart, and their printed difference is
// off by less than it is wide (13.3..13.6 is not "13..14"). `at_least` when
// they are equal.
inline int decimals_to_tell_apart(double a, double b, int at_least) {
  const double width = std::abs(a - b) * (1.0 + 1e-9);
  int d = at_least;
  while (d < 6 && width > 0.0 && std::pow(10.0, -d) > width) ++d;
  return d;
}

// "lo..hi" with at least `decimals` decimals, more where the ends would print alike.
inline std::string range_text(double lo, double hi, int decimals, std::string_view separator = "..") {
  const int d = decimals_to_tell_apart(lo, hi, decimals);
  return fmt::format("{:.{}f}{}{:.{}f}", lo, d, separator, hi, d);
}

// In single quotes for a POSIX shell (a ' inside written '\''): nothing
// inside is special to it.
inline std::string single_quoted(std::string_view s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A word for a shell: as it is when no character in it is special to one
// ("t=0.05,lag=0.3", "step@3600"), else single-quoted ("T^3", "T*dT").
inline std::string shell_word(std::string_view s) {
  bool plain = !s.empty();
  for (const char c : s)
    plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || std::string_view("._-+=,/:@%").find(c) != std::string_view::npos);
  return plain ? std::string(s) : single_quoted(s);
}

}  // namespace gyrotherm
