// deb.frequency_response: a path's H(j 2 pi f) at any frequencies, as the
// engine evaluates it (Path::Model: modal paths in blocks of frequencies,
// block diagrams frequency by frequency), on worker threads with the GIL
// released.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <complex>
#include <optional>
#include <vector>

#include "deb/budget/path.h"
#include "deb/core/error.h"
#include "python/src/arrays.h"
#include "python/src/bindings.h"

namespace deb::python {

void BindResponse(py::module_& m) {
  m.def(
      "frequency_response",
      [](const LoadedBudget& budget, const std::string& path_name, const py::handle& f, std::optional<int> threads) {
        const std::vector<double> f_hz = FiniteVector(f, "f");
        const int thread_count = ThreadCount(threads);
        const Path* path = nullptr;
        try {
          path = &budget.budget->FindPath(path_name);
        } catch (const InputError& e) {
          throw InputError("path", e.message());
        }
        const FrequencyModel model = path->Model();
        const auto p = static_cast<py::ssize_t>(model.outputs()), n = static_cast<py::ssize_t>(model.inputs());
        py::array_t<std::complex<double>> h({static_cast<py::ssize_t>(f_hz.size()), p, n});
        std::complex<double>* out = h.mutable_data();
        {
          py::gil_scoped_release release;
          // Row-major (n_f, outputs, inputs): H(f_k)[i, j] at out[(k p + i) n + j].
          model.ForEach(
              f_hz,
              [&](std::size_t k, const Eigen::MatrixXcd& hk) {
                for (py::ssize_t i = 0; i < p; ++i)
                  for (py::ssize_t j = 0; j < n; ++j) out[(static_cast<py::ssize_t>(k) * p + i) * n + j] = hk(i, j);
              },
              thread_count);
        }
        return h;
      },
      py::arg("budget"), py::arg("path"), py::arg("f"), py::kw_only(), py::arg("threads") = py::none());
}

}  // namespace deb::python
