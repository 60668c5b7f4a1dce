// deb._deb: the compiled part of the Python package deb (python/deb/).
#include <pybind11/pybind11.h>

#include "deb/version.h"
#include "python/src/bindings.h"

PYBIND11_MODULE(_deb, m) {
  m.doc() = "deb's C++ library for Python; use the package deb (docs/python.md)";
  m.attr("__version__") = DEB_VERSION;
  deb::python::BindErrors(m);
  deb::python::BindBudget(m);
  deb::python::BindResult(m);
  deb::python::BindResponse(m);
  deb::python::BindStudies(m);
  deb::python::BindDesignStudies(m);
}
