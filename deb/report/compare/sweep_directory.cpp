#include "deb/report/compare/sweep_directory.h"

#include <filesystem>

#include "deb/report/compare/overlay_plots.h"
#include "deb/report/compare/sweep_documents.h"

namespace deb::report {

namespace fs = std::filesystem;

std::string DefaultSweepDirectory(const std::string& budget_name) {
  return (fs::path("reports") / (budget_name + "_sweep")).string();
}

void WriteSweepDirectory(const std::string& name, const SweepSpec& spec, const std::vector<BudgetResult>& results,
                         const std::vector<Plot>& plots, const std::string& out_dir, const ReplaceOptions& replace,
                         int threads, const std::vector<StudySource>& sources) {
  const std::string csv = SweepCsv(spec, results);
  ReplaceDirectory(
      out_dir,
      [&](const std::string& tmp) {
        WriteTextFile((fs::path(tmp) / "sweep.csv").string(), csv);
        StudyDocument doc = SweepDocument(name, spec, results, plots);
        if (!sources.empty()) StampSources(&doc, sources);
        WriteTextFile((fs::path(tmp) / "sweep.md").string(), StudyMarkdown(doc));
        WriteTextFile((fs::path(tmp) / "sweep.html").string(), StudyHtml(doc));
        const std::string plots_dir = (fs::path(tmp) / "plots").string();
        if (!plots.empty()) {
          fs::create_directories(plots_dir);
          WritePlotsAsPng(plots, plots_dir, threads);
        }
        WriteStudyPdf(doc, plots_dir, (fs::path(tmp) / "sweep.pdf").string(), threads);
      },
      replace);
}

}  // namespace deb::report
