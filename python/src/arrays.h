// Internal: not part of the public API.
// numpy arrays in and out of the module. Out: read-only views of a result's
// vectors, which keep the result alive (no copy; a script that wants to
// change one copies it). In: a 1-D float64 array of finite values, or an
// InputError naming the argument.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

namespace deb::python {

namespace py = pybind11;

// A read-only 1-D view of `values`, which `owner` keeps alive.
py::array_t<double> View(const std::vector<double>& values, const std::shared_ptr<const void>& owner);

// `values` as float64 (any real dtype numpy converts safely; a list), 1-D
// (a scalar is one value), every value finite.
// @throws InputError naming `argument` otherwise.
std::vector<double> FiniteVector(const py::handle& values, const std::string& argument);

}  // namespace deb::python
