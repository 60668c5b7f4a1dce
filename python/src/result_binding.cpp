// deb.evaluate and its result: deb.Result, with per output (deb.Output) its
// PSD, CPS, variance and RMS, its contributors (deb.Contributor), bands and
// band requirements. Every object is a view into the one BudgetResult
// (shared), and every trace a read-only numpy view of its vector: nothing
// is copied, however many modes or frequencies.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/report/budget/file_digest.h"
#include "python/src/arrays.h"
#include "python/src/bindings.h"

namespace deb::python {
namespace {

struct OutputView {
  std::shared_ptr<const BudgetResult> result;
  std::size_t output = 0;
  const OutputResult& get() const { return result->outputs[output]; }
};

struct ContributorView {
  std::shared_ptr<const BudgetResult> result;
  std::size_t output = 0, contributor = 0;
  const ContributorResult& get() const { return result->outputs[output].contributors[contributor]; }
};

struct BandView {
  std::shared_ptr<const BudgetResult> result;
  std::size_t output = 0, band = 0;
  const BandResult& get() const { return result->outputs[output].bands[band]; }
};

struct RequirementView {
  std::shared_ptr<const BudgetResult> result;
  std::size_t output = 0, requirement = 0;
  const BandRequirementResult& get() const { return result->outputs[output].band_requirements[requirement]; }
};

OutputView OutputNamed(const EvaluatedBudget& r, const std::string& name) {
  std::string names;
  for (std::size_t o = 0; o < r.result->outputs.size(); ++o) {
    if (r.result->outputs[o].name == name) return {r.result, o};
    names += (names.empty() ? "" : ", ") + r.result->outputs[o].name;
  }
  throw InputError("name", "the budget has no output '" + name + "' (its outputs: " + names + ")");
}

ContributorView ContributorNamed(const OutputView& o, const std::string& name) {
  const auto& contributors = o.get().contributors;
  for (std::size_t c = 0; c < contributors.size(); ++c)
    if (contributors[c].name == name) return {o.result, o.output, c};
  throw InputError("name", "output '" + o.get().name + "' has no contributor '" + name + "'");
}

py::object OptionalDouble(const std::optional<double>& value) {
  return value ? py::object(py::float_(*value)) : py::object(py::none());
}

}  // namespace

int ThreadCount(const std::optional<int>& threads) {
  if (!threads) return 0;
  if (*threads < 1)
    throw InputError("threads", "must be at least 1 (or None for every core), got " + std::to_string(*threads));
  return *threads;
}

EvaluatedBudget EvaluateLoaded(const LoadedBudget& budget, int threads) {
  EngineOptions options;
  options.threads = threads;
  EvaluatedBudget out;
  out.info.budget_file = budget.file;
  out.info.budget_text = budget.text;
  // The digest summary.json names the budget by, as deb run computes it.
  if (budget.text) out.info.budget_sha256 = report::Sha256(*budget.text);
  else if (!budget.file.empty()) out.info.budget_sha256 = report::FileSha256(budget.file);
  out.info.threads = threads;
  py::gil_scoped_release release;
  const auto t0 = std::chrono::steady_clock::now();
  out.result = std::make_shared<const BudgetResult>(Evaluate(*budget.budget, options));
  out.info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

void BindResult(py::module_& m) {
  py::class_<ContributorView>(m, "Contributor", "A contributor (source x path) on one output")
      .def_property_readonly("name", [](const ContributorView& c) { return c.get().name; })
      .def_property_readonly("source", [](const ContributorView& c) { return c.get().source; })
      .def_property_readonly("path", [](const ContributorView& c) { return c.get().path; })
      .def_property_readonly("group", [](const ContributorView& c) { return c.get().group; })
      .def_property_readonly(
          "variance", [](const ContributorView& c) { return c.get().variance; },
          "Over the grid (CPS at its last point), output unit^2")
      .def_property_readonly("rms", [](const ContributorView& c) { return std::sqrt(c.get().variance); })
      .def_property_readonly(
          "psd", [](const ContributorView& c) { return View(c.get().psd, c.result); },
          "One-sided PSD on Result.f, output unit^2/Hz (read-only view)")
      .def_property_readonly(
          "cps", [](const ContributorView& c) { return View(c.get().cps, c.result); },
          "Forward cumulative power spectrum on Result.f, output unit^2")
      .def_property_readonly(
          "exact_variance", [](const ContributorView& c) { return OptionalDouble(c.get().exact_variance); },
          "Lyapunov variance over 0..infinity, or None (exact_note says why)")
      .def_property_readonly("exact_note", [](const ContributorView& c) { return c.get().exact_note; })
      .def_property_readonly("tail_variance_estimate",
                             [](const ContributorView& c) { return c.get().tail_variance_estimate; })
      .def_property_readonly(
          "tones",
          [](const ContributorView& c) {
            py::list out;
            for (const auto& t : c.get().tones) out.append(py::make_tuple(t.f_hz, t.variance));
            return out;
          },
          "[(f_hz, variance)] of the source's tones, included in cps and variance")
      .def("__repr__", [](const ContributorView& c) {
        return "<deb.Contributor '" + c.get().name + "' rms " + std::to_string(std::sqrt(c.get().variance)) + ">";
      });

  py::class_<BandView>(m, "Band", "An output's variance within a frequency band")
      .def_property_readonly("lo_hz", [](const BandView& b) { return b.get().band.lo_hz; })
      .def_property_readonly("hi_hz", [](const BandView& b) { return b.get().band.hi_hz; })
      .def_property_readonly("variance", [](const BandView& b) { return b.get().variance; })
      .def_property_readonly("rms", [](const BandView& b) { return std::sqrt(b.get().variance); })
      .def_property_readonly(
          "contributor_variance", [](const BandView& b) { return View(b.get().contributor_variance, b.result); },
          "Per contributor, in Output.contributors' order");

  py::class_<RequirementView>(m, "Requirement", "A band requirement (rms_max within lo_hz..hi_hz) and its verdict")
      .def_property_readonly("lo_hz", [](const RequirementView& r) { return r.get().requirement.lo_hz; })
      .def_property_readonly("hi_hz", [](const RequirementView& r) { return r.get().requirement.hi_hz; })
      .def_property_readonly("rms_max", [](const RequirementView& r) { return r.get().requirement.rms_max; })
      .def_property_readonly("variance", [](const RequirementView& r) { return r.get().variance; })
      .def_property_readonly("rms", [](const RequirementView& r) { return r.get().rms(); })
      .def_property_readonly("passed", [](const RequirementView& r) { return r.get().pass(); });

  py::class_<OutputView>(m, "Output", "An output: its total and its contributors")
      .def_property_readonly("name", [](const OutputView& o) { return o.get().name; })
      .def_property_readonly("signal", [](const OutputView& o) { return o.get().signal; })
      .def_property_readonly("unit", [](const OutputView& o) { return o.get().unit; })
      .def_property_readonly(
          "variance", [](const OutputView& o) { return o.get().variance; }, "output unit^2")
      .def_property_readonly("rms", [](const OutputView& o) { return o.get().rms(); })
      .def_property_readonly(
          "psd", [](const OutputView& o) { return View(o.get().total_psd, o.result); },
          "One-sided PSD of the total on Result.f, output unit^2/Hz")
      .def_property_readonly("cps", [](const OutputView& o) { return View(o.get().total_cps, o.result); })
      .def_property_readonly(
          "rms_max", [](const OutputView& o) { return OptionalDouble(o.get().rms_max); },
          "The whole-grid requirement, or None")
      .def_property_readonly(
          "passed", [](const OutputView& o) { return o.get().pass(); }, "rms <= rms_max (True without a requirement)")
      .def_property_readonly(
          "all_passed", [](const OutputView& o) { return o.get().AllPass(); }, "passed and every band requirement")
      .def_property_readonly("contributors",
                             [](const OutputView& o) {
                               std::vector<ContributorView> out;
                               for (std::size_t c = 0; c < o.get().contributors.size(); ++c)
                                 out.push_back({o.result, o.output, c});
                               return out;
                             })
      .def("contributor", &ContributorNamed, py::arg("name"))
      .def_property_readonly("bands",
                             [](const OutputView& o) {
                               std::vector<BandView> out;
                               for (std::size_t b = 0; b < o.get().bands.size(); ++b)
                                 out.push_back({o.result, o.output, b});
                               return out;
                             })
      .def_property_readonly(
          "requirements",
          [](const OutputView& o) {
            std::vector<RequirementView> out;
            for (std::size_t r = 0; r < o.get().band_requirements.size(); ++r) out.push_back({o.result, o.output, r});
            return out;
          },
          "The band requirements (rms_max is the whole-grid one)")
      .def("__repr__", [](const OutputView& o) {
        return "<deb.Output '" + o.get().name + "' rms " + std::to_string(o.get().rms()) + " " + o.get().unit + ">";
      });

  py::class_<EvaluatedBudget>(m, "Result", "An evaluated budget (deb.evaluate)")
      .def_property_readonly("name", [](const EvaluatedBudget& r) { return r.result->outline.name; })
      .def_property_readonly(
          "f", [](const EvaluatedBudget& r) { return View(r.result->grid.f_hz(), r.result); },
          "The frequency grid in Hz (read-only view)")
      .def_property_readonly("outputs",
                             [](const EvaluatedBudget& r) {
                               std::vector<OutputView> out;
                               for (std::size_t o = 0; o < r.result->outputs.size(); ++o) out.push_back({r.result, o});
                               return out;
                             })
      .def("output", &OutputNamed, py::arg("name"))
      .def_property_readonly("warnings", [](const EvaluatedBudget& r) { return r.result->warnings; })
      .def_property_readonly(
          "seconds", [](const EvaluatedBudget& r) { return OptionalDouble(r.info.seconds); },
          "Wall time of the evaluation")
      .def(
          "summary_json", [](const EvaluatedBudget& r) { return SummaryJson(*r.result, r.info); },
          "summary.json's text, as deb run writes it")
      .def("__repr__", [](const EvaluatedBudget& r) {
        return "<deb.Result '" + r.result->outline.name + "': " + std::to_string(r.result->grid.size()) +
               " frequencies, " + std::to_string(r.result->outputs.size()) + " outputs>";
      });

  m.def(
      "evaluate",
      [](const LoadedBudget& budget, std::optional<int> threads) {
        return EvaluateLoaded(budget, ThreadCount(threads));
      },
      py::arg("budget"), py::kw_only(), py::arg("threads") = py::none());
}

}  // namespace deb::python
