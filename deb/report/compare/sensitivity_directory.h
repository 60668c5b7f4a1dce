// Internal: not part of the public API.
// The directory `deb sensitivity` writes, atomically (ReplaceDirectory):
// sensitivity.csv (one row per parameter, output and term), sensitivity.md,
// sensitivity.html and sensitivity.pdf (study_document.h: the nominal
// parameters, then per output its terms ranked as RankedForOutput ranks
// them, with its tornado chart) and plots/<output>_tornado.png
// (sensitivity_plots.h) when there are plots.
#pragma once

#include <map>

#include <string>
#include <utility>
#include <vector>

#include "deb/budget/result.h"
#include "deb/budget/sensitivity.h"
#include "deb/core/output_dir.h"
#include "deb/report/compare/study_document.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

// A parameter's key path and the nominal values it reaches (one per number).
using NominalParameter = std::pair<std::string, std::vector<double>>;

// How a study was made: of budget `name`, with relative step `step`, from
// these nominal parameters.
struct SensitivitySetting {
  std::string name;
  double step = 0.0;
  std::vector<NominalParameter> parameters;
  // A parameter's name on tables and plots (deb sensitivity --label
  // KEY.PATH=TEXT), by key path; a parameter without one is named by it.
  std::map<std::string, std::string> labels;
  // The label of `key`, or the key path itself.
  std::string Label(const std::string& key) const;
};

// "50" for one value, "50 (all 6)" for several equal ones, else the list;
// "–" for none.
std::string NominalText(const std::vector<double>& values);

// parameter,output,unit,contributor,variance,d_variance_d_log_p,elasticity,method
// (exact | central_difference); 10 significant digits.
std::string SensitivityCsv(const std::vector<Sensitivity>& sensitivities);

// The study as a document, each output's tornado charts (Plot::output) in
// its section; `plots` outlive it.
StudyDocument SensitivityDocument(const SensitivitySetting& setting, const SensitivityStudy& study,
                                  const std::vector<Plot>& plots);

// reports/<budget-name>_sensitivity.
std::string DefaultSensitivityDirectory(const std::string& budget_name);

// Writes the directory, the plots drawn by `threads` gnuplot processes at a
// time (none when `plots` is empty).
// @throws WriteError as ReplaceDirectory; InputError if gnuplot is missing
//         or fails.
// `sources`: the budget file (StampSources).
void WriteSensitivityDirectory(const SensitivitySetting& setting, const SensitivityStudy& study,
                               const std::vector<Plot>& plots, const std::string& out_dir,
                               const ReplaceOptions& replace, int threads,
                               const std::vector<StudySource>& sources = {});

}  // namespace deb::report
