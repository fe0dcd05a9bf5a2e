#pragma once
// The parts of the extension module, one file each (python/src/*.cpp).

#include <pybind11/pybind11.h>

namespace gyrotherm::python {

// simulate (python/src/records.cpp).
void add_records(pybind11::module_& m);

}  // namespace gyrotherm::python
