// The studies over evaluated budgets: deb.sweep (a budget's sweep section,
// EvaluateSweep), deb.compare (Compare of two results' figures) and
// deb.write_report (the report directory of `deb run`,
// WriteReportDirectory). python/deb/_studies.py gives them their Python
// arguments (a file, a text or a dict; a sweep section written from Python).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/comparison.h"
#include "deb/budget/sweep.h"
#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/load/sweep_yaml.h"
#include "deb/report/budget/report_writer.h"
#include "deb/results/comparison_files.h"
#include "python/src/bindings.h"

namespace deb::python {
namespace {

// Every variant of a sweep and its result.
struct SweepOutcome {
  SweepSpec spec;
  std::vector<EvaluatedBudget> results;
  std::vector<BudgetResult> plain;  // the same results, as SweepCsv takes them
};

using Overrides = std::vector<std::pair<std::string, std::string>>;

SweepOutcome RunSweep(const SweepBudget& sweep, const RunInfo& info, int threads) {
  SweepOutcome out;
  out.spec = sweep.spec;
  {
    py::gil_scoped_release release;
    out.plain = EvaluateSweep(sweep.spec, sweep.variant, threads);
  }
  for (const BudgetResult& r : out.plain) out.results.push_back({std::make_shared<const BudgetResult>(r), info});
  return out;
}

py::dict FigureDict(const ComparedFigure& f) {
  py::dict d;
  d["output"] = f.output;
  d["unit"] = f.unit;
  d["contributor"] = f.contributor;
  d["band"] = f.band.empty() ? py::object(py::none()) : py::str(f.band);
  d["rms_a"] = f.rms_a;
  d["rms_b"] = f.rms_b;
  d["difference"] = f.difference;
  d["ratio"] = f.ratio ? py::object(py::float_(*f.ratio)) : py::object(py::none());
  d["variance_change_of_total"] = f.variance_change_of_total;
  d["negligible_a"] = f.negligible_a;
  d["negligible_b"] = f.negligible_b;
  return d;
}

py::list FigureList(const std::vector<ComparedFigure>& figures) {
  py::list out;
  for (const ComparedFigure& f : figures) out.append(FigureDict(f));
  return out;
}

}  // namespace

void BindStudies(py::module_& m) {
  py::class_<SweepOutcome>(m, "SweepResult", "Every variant of a sweep (deb.sweep) and its result")
      .def_property_readonly(
          "parameters",
          [](const SweepOutcome& s) {
            std::vector<std::string> names;
            for (const SweepParameter& p : s.spec.parameters) names.push_back(p.Name());
            return names;
          },
          "The swept parameters' names (label, or key path)")
      .def_property_readonly(
          "values",
          [](const SweepOutcome& s) {
            const std::vector<std::vector<double>> rows = s.spec.Variants();
            const auto cols = static_cast<py::ssize_t>(s.spec.parameters.size());
            py::array_t<double> v({static_cast<py::ssize_t>(rows.size()), cols});
            for (std::size_t i = 0; i < rows.size(); ++i)
              for (py::ssize_t k = 0; k < cols; ++k) v.mutable_at(i, k) = rows[i][k];
            return v;
          },
          "(variants, parameters): each variant's values (a textual parameter: its index)")
      .def_property_readonly("results", [](const SweepOutcome& s) { return s.results; })
      .def(
          "csv", [](const SweepOutcome& s) { return SweepCsv(s.spec, s.plain); },
          "The CSV deb sweep writes: one row per variant, every output's and contributor's RMS")
      .def("__len__", [](const SweepOutcome& s) { return s.results.size(); });

  m.def(
      "sweep_file",
      [](const std::string& path, const Overrides& overrides, std::optional<int> threads) {
        const int n = ThreadCount(threads);
        const SweepBudget sweep = LoadSweepFile(path, ToOverrides(overrides));
        return RunSweep(sweep, RunInfo(path), n);
      },
      py::arg("path"), py::arg("overrides"), py::arg("threads"));
  m.def(
      "sweep_text",
      [](const std::string& text, const std::string& name, const std::string& base_dir, const Overrides& overrides,
         std::optional<int> threads) {
        const int n = ThreadCount(threads);
        const SweepBudget sweep = LoadSweepText(text, name, base_dir, ToOverrides(overrides));
        RunInfo info;
        info.budget_text = text;
        return RunSweep(sweep, info, n);
      },
      py::arg("text"), py::arg("name"), py::arg("base_dir"), py::arg("overrides"), py::arg("threads"));

  py::class_<Comparison>(m, "Comparison", "Two results side by side (deb.compare): RMS, B - A, B / A")
      .def_property_readonly("label_a", [](const Comparison& c) { return c.label_a; })
      .def_property_readonly("label_b", [](const Comparison& c) { return c.label_b; })
      .def_property_readonly(
          "figures", [](const Comparison& c) { return FigureList(c.figures); },
          "Per output: the total, its contributors, then its bands; one dict each")
      .def_property_readonly("unmatched", [](const Comparison& c) { return c.unmatched; })
      .def_property_readonly("tolerance", [](const Comparison& c) { return c.tolerance; })
      .def(
          "largest_changes", [](const Comparison& c, std::size_t count) { return FigureList(c.LargestChanges(count)); },
          py::arg("count") = 3)
      .def(
          "moved", [](const Comparison& c, double rel) { return FigureList(c.Moved(rel)); }, py::arg("rel"))
      .def(
          "json", [](const Comparison& c) { return ComparisonJson(c); },
          "compare.json's text, as deb compare writes it")
      .def("csv", [](const Comparison& c) { return ComparisonCsv(c); });

  m.def(
      "compare",
      [](const EvaluatedBudget& a, const EvaluatedBudget& b, const std::string& label_a, const std::string& label_b,
         std::optional<double> tolerance) {
        if (tolerance && !(*tolerance >= 0.0))
          throw InputError("tolerance", "must be a relative change >= 0, got " + std::to_string(*tolerance));
        Comparison c = Compare(FiguresOf(label_a, *a.result), FiguresOf(label_b, *b.result));
        c.tolerance = tolerance;
        return c;
      },
      py::arg("a"), py::arg("b"), py::arg("label_a"), py::arg("label_b"), py::arg("tolerance"));

  m.def(
      "write_report",
      [](const EvaluatedBudget& result, const std::string& directory, bool plots,
         const std::vector<std::string>& formats, bool asd, bool reverse_cps, int digits, bool force,
         const std::vector<std::string>& exports, std::optional<int> threads) {
        ReportOptions options;
        options.plots = plots;
        options.plot_scripts = plots;
        options.formats.clear();
        for (const std::string& f : formats) options.formats.push_back(ParsePlotFormat(f));
        options.asd = asd;
        options.reverse_cps = reverse_cps;
        options.digits = digits;
        options.force = force;
        options.threads = ThreadCount(threads);
        std::vector<ExportFormat> export_formats;
        for (const std::string& e : exports) export_formats.push_back(ParseExportFormat(e));
        RunInfo info = result.info;
        info.threads = options.threads;
        if (Reproducible()) info.seconds.reset();  // as deb run: byte-identical files under SOURCE_DATE_EPOCH
        ReportManifest manifest;
        {
          py::gil_scoped_release release;
          manifest = WriteReportDirectory(*result.result, info, options, directory, export_formats);
        }
        py::dict d;
        d["files"] = manifest.files;
        d["plots"] = manifest.plots;
        d["pdf_pages"] = manifest.pdf_pages;
        return d;
      },
      py::arg("result"), py::arg("directory"), py::arg("plots"), py::arg("formats"), py::arg("asd"),
      py::arg("reverse_cps"), py::arg("digits"), py::arg("force"), py::arg("exports"), py::arg("threads"));
}

}  // namespace deb::python
