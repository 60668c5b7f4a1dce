// A budget's result as a MATLAB file (`deb run --export mat`: result.mat):
// the grid, and per output a struct with its traces (PSD and CPS per
// contributor and in total), figures, tones, bands, groups and references.
// It needs only the BudgetResult. The layout is docs/result_files.md's.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"

namespace deb {

// `name` as a valid MATLAB identifier of at most 63 characters: every
// character outside [A-Za-z0-9_] becomes '_', a name that does not start
// with a letter gets an 'x' in front (as MATLAB's matlab.lang.makeValidName
// does), and a name already in `taken` gets the first free suffix _2, _3, ...
// The result is added to `taken`.
std::string MatlabName(const std::string& name, std::vector<std::string>& taken);

// Writes result.mat's content into `file` (a MAT-file of version 7).
// @throws WriteError if it cannot be written (deb/formats/mat_file.h); nothing
//         is left at `file` then.
void WriteResultMat(const BudgetResult& result, const std::string& file);

}  // namespace deb
