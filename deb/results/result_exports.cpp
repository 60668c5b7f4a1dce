#include "deb/results/result_exports.h"

#include <algorithm>
#include <filesystem>

#include "deb/core/parallel.h"
#include "deb/core/output_dir.h"
#include "deb/results/result_mat.h"
#include "deb/results/result_writer.h"
#include "deb/results/result_xlsx.h"

namespace deb {

std::vector<std::string> ExportFileNames(const BudgetResult& result, ExportFormat format) {
  if (format != ExportFormat::kCsv) return {"result." + ToString(format)};
  std::vector<std::string> names;
  for (const OutputResult& o : result.outputs) names.push_back(OutputCsvName(o.name));
  return names;
}

std::vector<std::string> WriteResultExports(const BudgetResult& result, const std::vector<ExportFormat>& formats,
                                            const std::string& dir) {
  std::vector<std::string> written;
  std::vector<ExportFormat> done;
  for (const ExportFormat format : formats) {
    if (std::find(done.begin(), done.end(), format) != done.end()) continue;
    done.push_back(format);
    const std::vector<std::string> names = ExportFileNames(result, format);
    const auto file = [&](std::size_t i) { return (std::filesystem::path(dir) / names[i]).string(); };
    switch (format) {
      case ExportFormat::kCsv:
        // Formatting the numbers is most of the work: one output per job.
        ParallelForEach(names.size(), [&](std::size_t o) { WriteTextFile(file(o), OutputCsv(result, result.outputs[o])); });
        break;
      case ExportFormat::kMat: WriteResultMat(result, file(0)); break;
      case ExportFormat::kXlsx: WriteResultXlsx(result, file(0)); break;
    }
    written.insert(written.end(), names.begin(), names.end());
  }
  return written;
}

}  // namespace deb
