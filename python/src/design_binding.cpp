// The design studies over a budget file: deb.uncertainty (the tolerances'
// distributions sampled, RunUncertainty), deb.optimise (parameters within
// their bounds chosen, RunOptimise) and deb.sensitivity (every variance's
// derivatives, ComputeSensitivities). Each returns the summary.json text the
// CLI writes (parsed in python/deb/_studies.py) and the per-sample or
// per-evaluation tables as numpy arrays; the GIL is released while budgets
// are evaluated.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/sensitivity.h"
#include "deb/core/error.h"
#include "deb/load/optimise_yaml.h"
#include "deb/load/sweep_yaml.h"
#include "deb/load/uncertainty_yaml.h"
#include "deb/results/optimise_files.h"
#include "deb/results/uncertainty_files.h"
#include "python/src/bindings.h"

namespace deb::python {
namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;

}  // namespace

void BindDesignStudies(py::module_& m) {
  m.def(
      "uncertainty_file",
      [](const std::string& path, const Overrides& overrides, long long samples, const std::string& method,
         unsigned long long seed, std::optional<int> threads) {
        if (samples < 1 || samples > static_cast<long long>(kMaxUncertaintySamples))
          throw InputError("samples", "must be 1 to " + std::to_string(kMaxUncertaintySamples) + ", got " +
                                          std::to_string(samples));
        const UncertaintyBudget budget = LoadUncertaintyFile(path, ToOverrides(overrides));
        UncertaintyOptions options;
        options.samples = static_cast<std::size_t>(samples);
        options.method = ParseSamplingMethod(method);
        options.seed = seed;
        options.threads = ThreadCount(threads);
        UncertaintyResult r;
        {
          py::gil_scoped_release release;
          r = RunUncertainty(budget.spec, options, budget.variant);
        }
        const auto n = static_cast<py::ssize_t>(r.samples);
        const auto p = static_cast<py::ssize_t>(r.spec.parameters.size());
        const auto k = static_cast<py::ssize_t>(r.metrics.size());
        py::array_t<double> parameters({n, p}), metrics({n, k});
        for (py::ssize_t s = 0; s < n; ++s) {
          for (py::ssize_t i = 0; i < p; ++i)
            parameters.mutable_at(s, i) = r.parameter_values[static_cast<std::size_t>(i)][static_cast<std::size_t>(s)] /
                                          r.spec.parameters[static_cast<std::size_t>(i)].unit_si;
          for (py::ssize_t j = 0; j < k; ++j)
            metrics.mutable_at(s, j) = r.metrics[static_cast<std::size_t>(j)].values[static_cast<std::size_t>(s)];
        }
        std::vector<std::string> names;
        for (const StudyMetric& x : r.metrics) names.push_back(x.Name());
        return py::make_tuple(UncertaintySummaryJson(budget.name, r), parameters, names, metrics);
      },
      py::arg("path"), py::arg("overrides"), py::arg("samples"), py::arg("method"), py::arg("seed"),
      py::arg("threads"));

  m.def(
      "optimise_file",
      [](const std::string& path, const std::vector<std::string>& vary, const Overrides& overrides,
         const std::optional<std::string>& objective, const std::string& method, int starts, int max_evaluations,
         double tolerance, unsigned long long seed, std::optional<double> robust, int robust_samples,
         std::optional<int> threads) {
        if (starts < 1 || starts > kMaxOptimiseStarts || max_evaluations < 1 ||
            max_evaluations > kMaxEvaluationsPerStart || !(tolerance > 0.0 && tolerance <= 0.1) ||
            (robust && !(*robust > 0.0 && *robust < 100.0)) || robust_samples < 2 ||
            robust_samples > kMaxRobustSamples)
          throw InputError("arguments", "starts must be 1 to " + std::to_string(kMaxOptimiseStarts) +
                                            ", max_evaluations 1 to " + std::to_string(kMaxEvaluationsPerStart) +
                                            ", tolerance in (0, 0.1], robust a percentile in (0, 100) and "
                                            "robust_samples 2 to " + std::to_string(kMaxRobustSamples));
        const OptimiseBudget budget = LoadOptimiseFile(path, vary, ToOverrides(overrides), robust.has_value());
        const OptimiseObjective o = budget.Objective(objective.value_or(""), robust,
                                                     static_cast<std::size_t>(robust_samples), seed);
        OptimiseOptions options;
        options.method = ParseEnum<OptimiseMethod>(method, "optimisation method");
        options.starts = starts;
        options.max_evaluations = max_evaluations;
        options.tolerance = tolerance;
        options.seed = seed;
        options.threads = ThreadCount(threads);
        OptimiseResult r;
        {
          py::gil_scoped_release release;
          r = RunOptimise(budget.variables, o, options, budget.loader);
        }
        return py::make_tuple(OptimiseSummaryJson(budget.name, r), OptimiseHistoryCsv(r));
      },
      py::arg("path"), py::arg("vary"), py::arg("overrides"), py::arg("objective"), py::arg("method"),
      py::arg("starts"), py::arg("max_evaluations"), py::arg("tolerance"), py::arg("seed"), py::arg("robust"),
      py::arg("robust_samples"), py::arg("threads"));

  m.def(
      "sensitivity_file",
      [](const std::string& path, const std::vector<std::string>& parameters, const Overrides& overrides, double step,
         bool central_differences, std::optional<int> threads) {
        if (parameters.empty()) throw InputError("parameters", "name at least one parameter (or key path)");
        if (!(step >= 1e-8 && step <= 0.5))
          throw InputError("step", "must be a relative step in [1e-8, 0.5], got " + std::to_string(step));
        const std::vector<BudgetOverride> set = ToOverrides(overrides);
        const Budget budget = LoadBudgetFile(path, set);
        EngineOptions options;
        options.threads = ThreadCount(threads);
        options.response_traces = false;
        SensitivityStudy study;
        {
          py::gil_scoped_release release;
          study = ComputeSensitivities(
              budget, parameters, step,
              [&](const std::string& key, double factor) {
                return LoadBudgetWithScaledParameter(path, key, factor, set);
              },
              options,
              central_differences ? SensitivityMode::kCentralDifferences : SensitivityMode::kExactWherePossible);
        }
        py::list rows, methods;
        for (const Sensitivity& x : study.sensitivities)
          rows.append(py::dict(py::arg("parameter") = x.parameter, py::arg("output") = x.output,
                               py::arg("unit") = x.unit, py::arg("contributor") = x.contributor,
                               py::arg("variance") = x.variance, py::arg("d_variance_d_log_p") = x.d_variance_d_log_p,
                               py::arg("elasticity") = x.elasticity,
                               py::arg("method") = x.exact ? "exact" : "central_difference"));
        for (const SensitivityMethod& x : study.methods)
          methods.append(py::dict(py::arg("parameter") = x.parameter, py::arg("exact") = x.exact,
                                  py::arg("note") = x.note));
        return py::make_tuple(rows, methods);
      },
      py::arg("path"), py::arg("parameters"), py::arg("overrides"), py::arg("step"), py::arg("central_differences"),
      py::arg("threads"));
}

}  // namespace deb::python
