#pragma once
// Between numpy and the library: a record given as a mapping of column names
// to arrays becomes a fit::Table that views them (no copy for 1-D float64
// C-contiguous arrays), and vectors the library made become numpy arrays that
// own them (no copy either).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>


namespace gyrotherm::python {

namespace py = pybind11;

// `values` moved into a numpy array that owns it (freed with the array).
py::array_t<double> owning_array(std::vector<double>&& values);

}  // namespace gyrotherm::python
