// `deb sensitivity BUDGET.yaml -p KEY.PATH [-p ...]`: the derivative of every
// output's variance (total and per contributor) with respect to each named
// parameter, by central differences in ln p (deb/budget/sensitivity.h),
// ranked per output; sensitivity.csv and sensitivity.md are written
// atomically into reports/<budget-name>_sensitivity/ (or --out).
#pragma once

#include <CLI/CLI.hpp>

namespace deb::tools {

// Registers `sensitivity` on app.
CLI::App* AddSensitivityCommand(CLI::App& app);

// Runs `sensitivity` (after parsing).
// @throws InputError for a bad budget, a key path that reaches no number, or
//         a directory that cannot be written.
int RunSensitivityCommand(const CLI::App& sensitivity);

}  // namespace deb::tools
