// The files `deb run --export FORMAT` adds to a report directory: one CSV
// table per output (<output>.csv, deb/results/result_writer.h), a budget's
// result for MATLAB (result.mat, deb/results/result_mat.h) and for Excel
// (result.xlsx, deb/results/result_xlsx.h). Each needs only the BudgetResult;
// result.h5, always written, holds all of it.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/core/enum_names.h"

namespace deb {

enum class ExportFormat { kCsv, kMat, kXlsx };
inline constexpr EnumName<ExportFormat> kExportFormatNames[] = {
    {ExportFormat::kCsv, "csv"}, {ExportFormat::kMat, "mat"}, {ExportFormat::kXlsx, "xlsx"}};
constexpr EnumNames<ExportFormat> NamesOf(ExportFormat) { return kExportFormatNames; }
// @throws InputError "unknown export format '<text>'; allowed: csv, mat, xlsx".
inline ExportFormat ParseExportFormat(const std::string& text) { return ParseEnum<ExportFormat>(text, "export format"); }

// The files a format writes for `result`: each output's CSV
// (OutputCsvName), "result.mat", "result.xlsx".
std::vector<std::string> ExportFileNames(const BudgetResult& result, ExportFormat format);

// Writes each format's file (ExportFileName) into the existing directory
// `dir`, in the order given, each format once; returns the names written.
// @throws WriteError if one cannot be written.
std::vector<std::string> WriteResultExports(const BudgetResult& result, const std::vector<ExportFormat>& formats,
                                            const std::string& dir);

}  // namespace deb
