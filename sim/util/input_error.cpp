#include "sim/util/input_error.h"

#include <fmt/format.h>

namespace gyrotherm {

std::string located(const std::string& file, std::size_t line, const std::string& message) {
  return line > 0 ? fmt::format("{}:{}: {}", file, line, message)
                  : fmt::format("{}: {}", file, message);
}

}  // namespace gyrotherm
