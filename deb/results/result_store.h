// Internal: not part of the public API.
// The result store: result.h5, an HDF5 file beside summary.json that holds
// everything a report is drawn from (docs/result-store.md gives the schema):
// the frequency grid, every output's and contributor's PSD and CPS, tones,
// channel parts, bands, requirements, references, groups, loops with their
// margins, the traces of the paths and loops (response_traces.h), the
// budget's outline (budget_outline.h: names, units, descriptions; no model)
// and the budget file's text and SHA-256. `deb report RESULT_DIR` reads it back and redraws
// the report without evaluating anything; the .mat and .xlsx exports can be
// made from it too.
#pragma once

#include <string>

#include "deb/budget/result.h"
#include "deb/results/result_writer.h"

namespace deb {

// The schema's name and version, in every store (/schema, /schema_version).
// A reader refuses another name or a newer version. Version 2 (deb 0.1.0
// from this change on) compresses its numbers and keeps a path response
// shared by several contributors once; version 1 is read as well.
inline constexpr const char* kResultStoreSchema = "deb-result";
inline constexpr int kResultStoreVersion = 2;
// Its name in a report directory, beside summary.json.
inline constexpr const char* kResultStoreFile = "result.h5";

// Writes `file` (replacing it): the result with its outline. `result` must
// have its traces (EngineOptions::response_traces); info.budget_text and
// budget_sha256 are stored as they are (none: "").
// @throws WriteError if HDF5 cannot be loaded or the file cannot be written.
void WriteResultStore(const BudgetResult& result, const RunInfo& info, const std::string& file);

// The result with its outline and traces, without path analyses
// (BudgetResult::paths is empty); the run's budget_file, budget_text,
// budget_sha256 and seconds into *info if given.
// @throws InputError "<file>: ..." for a file that is not a store of this
//         schema (or of a newer version), or any object that is missing,
//         malformed or inconsistent (lengths that do not match the grid,
//         indices out of range).
BudgetResult ReadResultStore(const std::string& file, RunInfo* info = nullptr);

}  // namespace deb
