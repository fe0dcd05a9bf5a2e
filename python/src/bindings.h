#pragma once
// The parts of the extension module, one file each (python/src/*.cpp).

#include <pybind11/pybind11.h>

namespace gyrotherm::python {

// simulate (python/src/records.cpp).
void add_records(pybind11::module_& m);
// fit (python/src/fitting.cpp).
void add_fitting(pybind11::module_& m);
// diagnose, allan, compensate, export, plan, option_table (python/src/studies.cpp).
void add_studies(pybind11::module_& m);

}  // namespace gyrotherm::python
