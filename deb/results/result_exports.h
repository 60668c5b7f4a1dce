// The files `deb run --export FORMAT` adds to a report directory: a budget's
// result for MATLAB (result.mat, deb/results/result_mat.h) and for Excel
// (result.xlsx, deb/results/result_xlsx.h). Each needs only the BudgetResult.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/core/enum_names.h"

namespace deb {

enum class ExportFormat { kMat, kXlsx };
inline constexpr EnumName<ExportFormat> kExportFormatNames[] = {{ExportFormat::kMat, "mat"},
                                                                {ExportFormat::kXlsx, "xlsx"}};
constexpr EnumNames<ExportFormat> NamesOf(ExportFormat) { return kExportFormatNames; }
// @throws InputError "unknown export format '<text>'; allowed: mat, xlsx".
inline ExportFormat ParseExportFormat(const std::string& text) { return ParseEnum<ExportFormat>(text, "export format"); }

// "result.mat", "result.xlsx".
std::string ExportFileName(ExportFormat format);

// Writes each format's file (ExportFileName) into the existing directory
// `dir`, in the order given, each format once; returns the names written.
// @throws WriteError if one cannot be written.
std::vector<std::string> WriteResultExports(const BudgetResult& result, const std::vector<ExportFormat>& formats,
                                            const std::string& dir);

}  // namespace deb
