#include "deb/report/compare/comparison_directory.h"

#include <filesystem>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/file_name.h"
#include "deb/results/comparison_files.h"
#include "deb/results/result_store.h"
#include "deb/report/compare/comparison_documents.h"
#include "deb/report/compare/overlay_plots.h"

namespace deb::report {

namespace fs = std::filesystem;

bool IsComparisonBudgetFile(const std::string& path) {
  const fs::path p(path);
  return !fs::is_directory(p) && p.extension() != ".json";
}

ComparisonInput ReadComparisonResult(const std::string& path, bool with_result) {
  const fs::path p(path);
  if (!fs::is_directory(p)) {
    const std::string dir = fs::absolute(p).parent_path().filename().string();
    return {ReadSummaryFigures(path, dir.empty() ? p.stem().string() : dir), std::nullopt};
  }
  const fs::path summary = p / "summary.json";
  if (!fs::exists(summary))
    throw InputError(path + ": a directory given to compare must hold summary.json (written by deb run)");
  ComparisonInput input{
      ReadSummaryFigures(summary.string(),
                         p.filename().empty() ? p.parent_path().filename().string() : p.filename().string()),
      std::nullopt};
  // With its result store, a directory is drawn as a budget is.
  const fs::path store = p / kResultStoreFile;
  if (with_result && fs::is_regular_file(store)) input.result = ReadResultStore(store.string());
  return input;
}

std::string DefaultComparisonDirectory(const std::string& label_a, const std::string& label_b) {
  return (fs::path("reports") / ("compare_" + FileNameWord(label_a) + "_vs_" + FileNameWord(label_b))).string();
}

void WriteComparisonDirectory(const Comparison& cmp, const std::vector<Plot>& plots, const std::string& out_dir,
                              const ReplaceOptions& replace, int threads, const std::vector<StudySource>& sources) {
  ReplaceDirectory(
      out_dir,
      [&](const std::string& dir) {
        const std::string plots_dir = (fs::path(dir) / "plots").string();
        if (!plots.empty()) {
          fs::create_directories(plots_dir);
          WritePlotsAsPng(plots, plots_dir, threads);
        }
        StudyDocument doc = ComparisonDocument(cmp, plots);
        if (!sources.empty()) StampSources(&doc, sources);
        WriteStudyPdf(doc, plots_dir, (fs::path(dir) / "compare.pdf").string(), threads);
        const std::vector<std::pair<std::string, std::string>> files = {{"compare.json", ComparisonJson(cmp)},
                                                                        {"compare.md", StudyMarkdown(doc)},
                                                                        {"compare.html", StudyHtml(doc)},
                                                                        {"compare.csv", ComparisonCsv(cmp)}};
        for (const auto& [name, text] : files) WriteTextFile((fs::path(dir) / name).string(), text);
      },
      replace);
}

}  // namespace deb::report
