// gyrotherm.simulate: a scenario run in memory; the record's columns as numpy
// arrays that own the simulator's vectors, its truth as the JSON text
// `simulate` writes beside its CSV, and the run's summary (`simulate --json`).

#include <pybind11/stl.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "python/src/arrays.h"
#include "python/src/bindings.h"
#include "python/src/keywords.h"
#include "sim/output.h"
#include "sim/simulation_run.h"
#include "studies/options/simulate_options.h"

namespace gyrotherm::python {

namespace {

py::dict simulate(const Keywords& keywords) {
  const sim::SimulateRequest request =
      studies::simulate_request(read_keywords(studies::simulate_option_table(), keywords, {"output"}));
  sim::Simulation s;
  {
    py::gil_scoped_release free;
    s = sim::simulate(request);
    if (!request.output.empty()) {  // the CLI's files too
      sim::write_simulation(request.output, *s.simulator, s.result);
      s.run.truth_file = sim::truth_path_for(request.output).string();
    }
    if (!request.plot.empty()) sim::plot_simulation(request.plot, *s.simulator, s.result);
  }
  py::dict out;
  out["truth"] = sim::truth_json(*s.simulator, s.result);
  nlohmann::ordered_json summary = sim::simulation_json(s.run);
  if (request.output.empty()) {
    summary["csv"] = nullptr;
    summary["truth"] = nullptr;
  }
  out["summary"] = summary.dump();
  py::dict columns;
  sim::SimulationResult& r = s.result;
  columns["time_s"] = owning_array(std::move(r.time_s));
  columns["chamber_c"] = owning_array(std::move(r.chamber_c));
  columns["case_c"] = owning_array(std::move(r.case_c));
  columns["temp_c"] = owning_array(std::move(r.temp_c));
  columns["temp2_c"] = owning_array(std::move(r.temp2_c));
  columns["gyro_dph"] = owning_array(std::move(r.gyro_dph));
  columns["bias_true_dph"] = owning_array(std::move(r.bias_true_dph));
  out["columns"] = columns;
  return out;
}

}  // namespace

void add_records(py::module_& m) {
  m.def("simulate", &simulate, py::arg("options"),
        "Runs a scenario in memory: {'columns': {name: array}, 'truth': JSON text, 'summary': JSON text}.");
}

}  // namespace gyrotherm::python
