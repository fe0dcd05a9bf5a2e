#include "python/src/keywords.h"

#include <string>

#include "sim/util/input_error.h"

namespace gyrotherm::python {

// Interim: replaced by the option tables.
sim::SimulateRequest simulate_request(const Keywords& keywords) {
  sim::SimulateRequest r;
  for (const auto& [k, v] : keywords) {
    if (k == "scenario") r.scenario = v;
    else if (k == "seed") r.seed = std::stoull(v);
    else if (k == "hidden") r.hidden.push_back(v);
    else if (k == "rig") r.rig = v;
    else if (k == "gyro") r.gyro = v;
    else if (k == "output") r.output = v;
    else if (k == "plot") r.plot = v;
    else throw InputError("unknown option " + k);
  }
  return r;
}

}  // namespace gyrotherm::python
