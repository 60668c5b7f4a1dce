#include "python/src/arrays.h"

#include <cmath>

#include "deb/core/error.h"

namespace deb::python {

py::array_t<double> View(const std::vector<double>& values, const std::shared_ptr<const void>& owner) {
  // The capsule holds a reference to the result: the array outlives the
  // Python objects it came from without dangling.
  auto* keep = new std::shared_ptr<const void>(owner);
  const py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<const void>*>(p); });
  py::array_t<double> array({values.size()}, {sizeof(double)}, values.data(), base);
  py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return array;
}

std::vector<double> FiniteVector(const py::handle& values, const std::string& argument) {
  const py::array raw = py::array::ensure(values);
  if (!raw) throw InputError(argument, "expected an array of numbers");
  const char kind = raw.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw InputError(argument, "expected real numbers, got an array of dtype " + std::string(py::str(raw.dtype())));
  if (raw.ndim() > 1)
    throw InputError(argument, "expected a 1-D array, got " + std::to_string(raw.ndim()) + " dimensions");
  const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(raw);
  std::vector<double> out(array.data(), array.data() + array.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      throw InputError(
          argument, "element " + std::to_string(i) + " is " + std::to_string(out[i]) + "; every value must be finite");
  return out;
}

}  // namespace deb::python
