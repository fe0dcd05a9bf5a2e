#pragma once
// Bad user input (a file, a key, a value, an option) is reported by throwing
// InputError with a message that names where the problem is and what was
// expected. The CLI turns it into exit code 2. Broken invariants are asserts,
// not InputErrors.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace gyrotherm {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// "file:line: message", or "file: message" when the line is unknown (0).
std::string located(const std::string& file, std::size_t line, const std::string& message);

}  // namespace gyrotherm
