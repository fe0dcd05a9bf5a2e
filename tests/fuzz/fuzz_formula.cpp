// libFuzzer target: the model-formula parser and the --hidden option parser.

#include <cstdint>
#include <string>

#include "fit/model/formula.h"
#include "sim/config_loader.h"
#include "sim/util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto terms = gyrotherm::fit::parse_formula(text);
    if (gyrotherm::fit::parse_formula(gyrotherm::fit::formula_text(terms)) != terms) __builtin_trap();
  } catch (const gyrotherm::InputError&) {
  }
  try {
    gyrotherm::sim::GyroConfig g;
    gyrotherm::sim::apply_hidden_option(g, text);
  } catch (const gyrotherm::InputError&) {
  }
  return 0;
}
