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

// A model that cannot be fitted on this data (too few points, a constant or
// collinear regressor, a covariance that is not positive definite). It is an
// InputError, so the command line still says why and exits 2 when the user's
// own model is the cause; code that tries models of its own (diagnose's
// candidates, a cross-validation fold) catches this type alone, so a real
// input error is never mistaken for "this candidate does not fit".
class FitError : public InputError {
 public:
  explicit FitError(const std::string& message) : InputError(message) {}
};

// "file:line: message", or "file: message" when the line is unknown (0).
std::string located(const std::string& file, std::size_t line, const std::string& message);

}  // namespace gyrotherm
