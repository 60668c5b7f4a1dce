// `deb compare A B [C ...]`: compares design options. Each argument is a
// budget (evaluated here) or a result directory of `deb run` (its
// summary.json is read). Every further argument is compared with the first;
// each comparison is written, atomically, as compare.json, compare.md,
// compare.html and compare.csv (and overlay plots when both are budgets)
// into reports/compare_<A>_vs_<B>/ (or --out for two arguments).
#pragma once

#include <CLI/CLI.hpp>

namespace deb::tools {

// Registers `compare` on app.
CLI::App* AddCompareCommand(CLI::App& app);

// Runs `compare` (after parsing).
// @throws InputError for an unreadable budget or result directory, or a
//         report directory that cannot be written.
int RunCompareCommand(const CLI::App& compare);

}  // namespace deb::tools
