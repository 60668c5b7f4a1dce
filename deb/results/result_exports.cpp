#include "deb/results/result_exports.h"

#include <algorithm>
#include <filesystem>

#include "deb/results/result_mat.h"
#include "deb/results/result_xlsx.h"

namespace deb {

std::string ExportFileName(ExportFormat format) { return "result." + ToString(format); }

std::vector<std::string> WriteResultExports(const BudgetResult& result, const std::vector<ExportFormat>& formats,
                                            const std::string& dir) {
  std::vector<std::string> written;
  std::vector<ExportFormat> done;
  for (const ExportFormat format : formats) {
    if (std::find(done.begin(), done.end(), format) != done.end()) continue;
    done.push_back(format);
    const std::string name = ExportFileName(format);
    const std::string file = (std::filesystem::path(dir) / name).string();
    switch (format) {
      case ExportFormat::kMat: WriteResultMat(result, file); break;
      case ExportFormat::kXlsx: WriteResultXlsx(result, file); break;
    }
    written.push_back(name);
  }
  return written;
}

}  // namespace deb
