#include "python/src/arrays.h"


namespace gyrotherm::python {

py::array_t<double> owning_array(std::vector<double>&& values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({owned->size()}, {sizeof(double)}, owned->data(), free_when_done);
}

}  // namespace gyrotherm::python
