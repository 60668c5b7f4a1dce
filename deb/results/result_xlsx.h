// A budget's result as an Excel workbook (`deb run --export xlsx`:
// result.xlsx): a Summary sheet (per output its RMS, requirement, verdict and
// largest contributor), and per output a contributor table, a band table and
// its traces (PSD and CPS per contributor and in total). It needs only the
// BudgetResult. The layout is docs/result_files.md's.
#pragma once

#include <string>

#include "deb/budget/result.h"

namespace deb {

// Writes result.xlsx's content into `file`.
// @throws WriteError if it cannot be written (deb/formats/xlsx_file.h); nothing
//         is left at `file` then.
void WriteResultXlsx(const BudgetResult& result, const std::string& file);

}  // namespace deb
