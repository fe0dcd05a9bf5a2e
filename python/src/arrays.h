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

#include "fit/data/table.h"
#include "sim/util/input_error.h"

namespace gyrotherm::python {

namespace py = pybind11;

// A table over the mapping's arrays, and what keeps them alive. Each value must
// be a 1-D array of real numbers (or convertible to one): one that is not
// float64 and C-contiguous is copied once (np.ascontiguousarray). A column of
// more than one dimension, or of complex, boolean, text or object values, is
// left out of the table and named in the error if the record needs it:
// columns the record does not use may hold anything.
struct TableHold {
  fit::Table table;
  std::vector<py::object> arrays;          // owners of the views
  std::vector<std::string> not_numbers;    // "label (dtype <U5)"
};
std::unique_ptr<TableHold> table_of(const py::handle& mapping, const std::string& name);

// work(), its InputError completed by the columns left out as not numbers
// (a missing column may be one of them).
template <class Work>
auto with_table_context(const TableHold& hold, Work&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const InputError& e) {
    if (hold.not_numbers.empty()) throw;
    std::string names;
    for (const std::string& n : hold.not_numbers) names += (names.empty() ? "" : ", ") + n;
    throw InputError(std::string(e.what()) + "; left out as not numbers: " + names);
  }
}

// `values` moved into a numpy array that owns it (freed with the array).
py::array_t<double> owning_array(std::vector<double>&& values);

}  // namespace gyrotherm::python
