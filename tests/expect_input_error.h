#pragma once
// Expects f() to throw InputError whose message contains every fragment.

#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim/util/input_error.h"

namespace gyrotherm::testing {

inline void expect_input_error(const std::function<void()>& f,
                               const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& e) {
    for (const std::string& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "message: " << e.what() << "\nmissing: " << fragment;
  }
}

}  // namespace gyrotherm::testing
