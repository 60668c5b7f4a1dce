// Internal: not part of the public API.
// The figures of index.html, drawn in the browser from the report's data so
// that the page is one file: per output the stacked CPS with its requirement,
// the PSD (or ASD) of every contributor and the total, the variance per band,
// and every contributor's path magnitude; hover shows the values, the
// legend's boxes hide contributors, a drag zooms the frequency axis (an
// output's CPS and PSD together), a double-click shows the whole grid.
//
// A budget's grid can hold 10^4 points and more, far more than a screen can
// show: each figure's frequencies are thinned by PlotPoints (peaks, notches
// and jumps are kept) over the whole grid at 2e-3 decade, then what remains
// again at twice the tolerance until at most kMaxFigurePoints remain (their
// chords stay within twice the last tolerance of the grid); values keep 4 significant
// digits, frequencies 7 (a grid holds a jump, e.g. at a band edge, as two
// points 1e-12 apart: they may print alike).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "deb/budget/result.h"

namespace deb::report {

constexpr std::size_t kMaxFigurePoints = 2000;

// Grid indices of a figure: the union of PlotPoints over `log_series` (log y)
// and `linear_series` (linear y), over the whole grid, at most max_points.
std::vector<std::size_t> FigurePoints(const std::vector<double>& f_hz,
                                      const std::vector<const std::vector<double>*>& log_series,
                                      const std::vector<const std::vector<double>*>& linear_series,
                                      std::size_t max_points = kMaxFigurePoints);

// The data of every figure, as JSON (see interactive_figures.cpp for its
// fields), safe inside a <script> element: every '<' is written \u003c.
// @throws InputError as ComputePathResponses.
std::string FigureDataJson(const BudgetResult& result, int threads = 0);

// The <figure> elements the script fills: for output `index`, kind "cps",
// "psd" (or "asd": the same, opened as amplitudes) or "bands"; for paths,
// kind "path" and the index into the data's paths (contributors outer,
// outputs inner). The caption is HTML.
std::string FigureElement(const std::string& kind, std::size_t index, const std::string& caption_html);

// The page's <script> elements: dygraphs, the data, the drawing code
// (index_figures.js).
std::string FigureScripts(const std::string& data_json);
std::string FigureCss();

}  // namespace deb::report
