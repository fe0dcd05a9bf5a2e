#pragma once
// Numbers in messages, formatted for people: five significant digits, no
// binary noise ("7324.6 s", not "7324.610000000001 s").

#include <fmt/format.h>

#include <string>

namespace gyrotherm {

inline std::string human(double v) { return fmt::format("{:.5g}", v); }

}  // namespace gyrotherm
