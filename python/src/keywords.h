#pragma once
// Keyword options from Python (name → value as text, lists as repeated
// pairs) read by each command's option table, the CLI's own
// (studies/options/): the same names, parsing, defaults and messages.

#include <string>
#include <utility>
#include <vector>

#include "sim/simulation_run.h"

namespace gyrotherm::python {

using Keywords = std::vector<std::pair<std::string, std::string>>;

sim::SimulateRequest simulate_request(const Keywords& keywords);

}  // namespace gyrotherm::python
