// The extension module gyrotherm._gyrotherm: the library's commands for the
// Python package (python/gyrotherm/__init__.py wraps them). Each function
// takes the command's options as keyword → text pairs read by the command's
// own option table (the CLI's), does its work with the GIL released, and
// returns what the CLI prints (JSON and text) with the arrays beside it.
//
// Errors: gyrotherm.InputError (a ValueError) carries the CLI's message for
// bad input (the CLI's exit code 2), gyrotherm.SolverError (a RuntimeError) a
// failed thermal simulation; anything else is a RuntimeError.

#include <pybind11/pybind11.h>
#include <nlohmann/json.hpp>

#include "fit/engines/engine_listing.h"
#include "fit/model/term_listing.h"
#include "python/src/bindings.h"
#include "sim/cvode_solver.h"
#include "sim/util/input_error.h"

namespace py = pybind11;

PYBIND11_MODULE(_gyrotherm, m) {
  m.doc() = "gyrotherm's library (use the package gyrotherm, not this module)";
  py::register_exception<gyrotherm::InputError>(m, "InputError", PyExc_ValueError);
  static py::exception<gyrotherm::sim::SolverError> solver_error(m, "SolverError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gyrotherm::sim::SolverError& e) {
      const std::string text = std::string("the thermal simulation failed: ") + e.what() +
                               "\nCheck the rig's capacities and conductances for values far outside the physical range.";
      solver_error(text.c_str());
    }
  });
  m.def("effects_json", [] { return gyrotherm::fit::effects_json().dump(); },
        "The model terms as `gyrotherm effects --json` prints them (a JSON text).");
  m.def("engines_json", [] { return gyrotherm::fit::engines_json().dump(); },
        "The fitting engines as `gyrotherm engines --json` prints them (a JSON text).");
  gyrotherm::python::add_records(m);
  gyrotherm::python::add_fitting(m);
  gyrotherm::python::add_studies(m);
}
