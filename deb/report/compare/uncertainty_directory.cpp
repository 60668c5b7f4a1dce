#include "deb/report/compare/uncertainty_directory.h"

#include <filesystem>

#include "deb/report/compare/overlay_plots.h"
#include "deb/report/compare/uncertainty_documents.h"
#include "deb/results/uncertainty_files.h"

namespace deb::report {

namespace fs = std::filesystem;

std::string DefaultUncertaintyDirectory(const std::string& budget_name) {
  return (fs::path("reports") / (budget_name + "_uncertainty")).string();
}

void WriteUncertaintyDirectory(const std::string& budget_name, const UncertaintyResult& result,
                               const std::vector<Plot>& plots, const std::string& out_dir,
                               const ReplaceOptions& replace, int threads, const std::vector<StudySource>& sources) {
  const std::string json = UncertaintySummaryJson(budget_name, result);
  ReplaceDirectory(
      out_dir,
      [&](const std::string& tmp) {
        WriteTextFile((fs::path(tmp) / "summary.json").string(), json);
        WriteTextFileFrom((fs::path(tmp) / "samples.csv").string(),
                          [&](const TextSink& put) { UncertaintySamplesCsv(result, put); });
        WriteUncertaintyStore((fs::path(tmp) / "result.h5").string(), budget_name, result);
        StudyDocument doc = UncertaintyDocument(budget_name, result, plots);
        if (!sources.empty()) StampSources(&doc, sources);
        WriteTextFile((fs::path(tmp) / "uncertainty.md").string(), StudyMarkdown(doc));
        WriteTextFile((fs::path(tmp) / "uncertainty.html").string(), StudyHtml(doc));
        const std::string plots_dir = (fs::path(tmp) / "plots").string();
        if (!plots.empty()) {
          fs::create_directories(plots_dir);
          WritePlotsAsPng(plots, plots_dir, threads);
        }
        WriteStudyPdf(doc, plots_dir, (fs::path(tmp) / "uncertainty.pdf").string(), threads);
      },
      replace);
}

}  // namespace deb::report
