// deb's errors as Python exceptions: InputError (bad input: a budget, a
// value, an array) as deb.InputError, a ValueError carrying where; WriteError
// (a report that cannot be written) as deb.WriteError, an OSError. The
// classes are Python's (python/deb/_errors.py), so that the package's
// Python code raises the same ones.
#include <pybind11/pybind11.h>

#include <exception>

#include "deb/core/error.h"
#include "python/src/bindings.h"

namespace deb::python {
namespace {

py::object ErrorClass(const char* name) { return py::module_::import("deb._errors").attr(name); }

// 0 and "" (not known) as None.
py::object OrNone(const std::string& text) { return text.empty() ? py::object(py::none()) : py::str(text); }
py::object OrNone(int number) { return number == 0 ? py::object(py::none()) : py::int_(number); }

}  // namespace

void BindErrors(py::module_&) {
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const InputError& e) {
      const py::object type = ErrorClass("InputError");
      const py::object value = type(e.what(), py::arg("message") = e.message(), py::arg("file") = OrNone(e.file()),
                                    py::arg("line") = OrNone(e.line()), py::arg("column") = OrNone(e.column()),
                                    py::arg("key_path") = OrNone(e.key_path()));
      PyErr_SetObject(type.ptr(), value.ptr());
    } catch (const WriteError& e) {
      const py::object type = ErrorClass("WriteError");
      PyErr_SetObject(type.ptr(), type(e.what()).ptr());
    }
  });
}

}  // namespace deb::python
