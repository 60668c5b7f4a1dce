// `deb sweep BUDGET.yaml`: evaluates every variant of a budget's `sweep`
// section (deb/io/sweep_yaml.h), variants in parallel, and writes sweep.csv
// (one row per variant: parameter values, RMS per output and contributor)
// and plots/<output>_sweep.png (RMS against the first parameter) atomically
// into reports/<budget-name>_sweep/ (or --out).
#pragma once

#include <CLI/CLI.hpp>

namespace deb::tools {

// Registers `sweep` on app.
CLI::App* AddSweepCommand(CLI::App& app);

// Runs `sweep` (after parsing).
// @throws InputError for a bad budget or sweep section, a variant that cannot
//         be evaluated, or a directory that cannot be written.
int RunSweepCommand(const CLI::App& sweep);

}  // namespace deb::tools
