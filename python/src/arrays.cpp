#include "python/src/arrays.h"

#include <fmt/format.h>

#include "sim/util/input_error.h"

namespace gyrotherm::python {

namespace {

// The column as a native float64 C-contiguous array (the same object when it is one),
// or none with `why` saying what it holds instead.
py::object numeric_column(const std::string& name, const py::handle& value, std::string& why) {
  py::object array = py::isinstance<py::array>(value) ? py::reinterpret_borrow<py::object>(value)
                                                      : py::module_::import("numpy").attr("asarray")(value);
  const py::array a = array.cast<py::array>();
  if (a.ndim() != 1) {
    why = fmt::format("{} (a {}-D array of shape {}; a column is 1-D)", name, a.ndim(),
                      py::str(array.attr("shape")).cast<std::string>());
    return py::none();
  }
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    why = fmt::format("{} (dtype {})", name, py::str(a.dtype()).cast<std::string>());
    return py::none();
  }
  // The same array when it is native float64 and C-contiguous; else a float64 copy.
  auto converted = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!converted) throw py::error_already_set();
  return converted;
}

}  // namespace

std::unique_ptr<TableHold> table_of(const py::handle& mapping, const std::string& name) {
  auto hold = std::make_unique<TableHold>();
  hold->table.name = name;
  const py::object items = mapping.attr("items")();
  for (const py::handle item : items) {
    const auto pair = item.cast<py::tuple>();
    if (!py::isinstance<py::str>(pair[0]))
      throw InputError(fmt::format("column names must be text; got {}", py::repr(pair[0]).cast<std::string>()));
    const std::string column = pair[0].cast<std::string>();
    std::string why;
    py::object array = numeric_column(column, pair[1], why);
    if (array.is_none()) {
      hold->not_numbers.push_back(why);
      continue;
    }
    const auto a = py::reinterpret_borrow<py::array_t<double, py::array::c_style>>(array);
    hold->table.columns.push_back({column, a.data(), static_cast<std::size_t>(a.shape(0))});
    hold->arrays.push_back(std::move(array));
  }
  return hold;
}

py::array_t<double> owning_array(std::vector<double>&& values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({owned->size()}, {sizeof(double)}, owned->data(), free_when_done);
}

}  // namespace gyrotherm::python
