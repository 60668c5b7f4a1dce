// Internal: not part of the public API.
// One plot of a report, as data: the CSV behind it and a gnuplot script that
// draws it from that CSV. The script holds no terminal or output file, so the
// same text draws the PNG, the SVG and the page of report.pdf; it is saved
// beside the CSV (plots/<name>.gp) so that a reader can redraw or restyle it.
// Also the text helpers every plot builder needs (quoting, enhanced-text
// escapes, unit and number labels).
#pragma once

#include <string>
#include <vector>

#include "deb/core/rounding_zero.h"
#include "deb/report/figure/plot_figure.h"

namespace deb::report {

enum class PlotKind { kCps, kReverseCps, kSpectrum, kBands, kPath, kOverview };

struct Plot {
  std::string name;     // file stem under plots/, e.g. "z_velocity_cps"
  std::string caption;  // one sentence for index.html and report.md
  std::string label;    // a line naming what it shows, for a list of figures ("" for the caption)
  PlotKind kind = PlotKind::kCps;
  // Height of its figure in report.pdf or a study's PDF, on a canvas 662 px
  // wide (PdfFigureTerminal); 0: by its kind.
  int pdf_height_px = 0;
  int output = -1;      // index of the output it belongs to, -1 for none
  std::string csv;      // the data, written as plots/<name>.csv
  std::string script;   // gnuplot commands; the working directory is plots/
  // What the script draws, as data (figure_script.h emits the script from it);
  // empty for plots still written as text.
  PlotFigure figure;
};

// The one way user text reaches gnuplot: a string literal in single quotes
// ('' stands for '), inside which gnuplot expands neither `backquotes` nor
// @macros; control characters (a line break would end the command) become
// spaces. gnuplot_runner.h's CheckScript refuses any script that strays.
std::string Quote(const std::string& text);
// A file name for gnuplot (set output, load, a plot's data file): Quote, and
// "./" before a relative name that starts with '|', '<' or '!', which gnuplot
// would take for a pipe to a shell or a command to read from.
std::string QuoteFile(const std::string& path);
// The commands that draw a plot's script `script_file` into `output_file`
// with `terminal` (its "set terminal ..." line): set output, load, unset
// output, both names quoted by QuoteFile.
std::string DrawCommands(const std::string& terminal, const std::string& output_file, const std::string& script_file);
// Several lines as one gnuplot string expression: single-quoted lines
// joined by "\n", e.g. ('first'."\n".'second'); usable wherever a string is.
std::string QuoteLines(const std::vector<std::string>& lines);
// The same, split at the line breaks of `text`.
std::string QuoteLines(const std::string& text);

// Text safe inside gnuplot's enhanced mode: _ ^ @ & ~ { } \ are escaped, so
// that a name such as sensor_noise is not typeset with a subscript.
std::string Enhanced(const std::string& text);

// A unit for an enhanced-mode label: "um/s" -> "µm/s", "(um/s)^2/Hz" ->
// "(µm/s)^{2}/Hz", "nm/sqrt(Hz)" -> "nm/√Hz"; everything else escaped.
std::string UnitLabel(const std::string& unit);

// Unit of a variance (and of a CPS): "um/s" -> "(um/s)^2", "nm" -> "nm^2".
std::string VarianceUnit(const std::string& unit);

// "nm^2" -> "nm²": for text that can show the superscript (tables, pages).
std::string Squared(std::string unit);

// A unit for plain text (HTML, Markdown, the PDF's title page): the same
// micro sign and square root, exponents left as "^2".
std::string UnitText(const std::string& unit);

// `value` to `digits` significant digits: fixed notation for magnitudes in
// [1e-3, 1e5) ("12.3", "0.0523", "12300"), else "1.23e-05".
std::string Sig(double value, int digits = 3);
// The same for enhanced-mode labels: "1.23·10^{-5}".
std::string SigLabel(double value, int digits = 3);

// Short text of a value the user wrote (a requirement, a band edge):
// at most 6 significant digits, no trailing zeros ("20", "0.1", "2.5e-07").
std::string Short(double value);

// A share of a variance in percent: "78.1 %", "< 0.01 %" (in size; a
// share can be negative: a mode's cross-spectrum with the output).
std::string Share(double part, double whole);

// RoundingZero and WithoutRounding: deb/core/rounding_zero.h.

// A frequency for an enhanced-mode label: powers of ten from 10^4 up or
// 10^-4 down as "10^{8}", anything else as Short.
std::string HzLabel(double f_hz);
// The same for text (tables, captions, pages): "10⁸" in superscript digits
// rather than "1e+08"; other values as Short.
std::string HzText(double f_hz);

// A name as a file stem: characters outside [A-Za-z0-9_.-] become '_'; a
// stem longer than 100 characters keeps its first 80 and a hash of the
// whole name, so that a file named after two names stays within the 255
// bytes a file name may have.
std::string FileStem(const std::string& name);

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string CsvField(const std::string& text);

// Number text for CSV files (10 significant digits).
std::string CsvNumber(double value);

// One gnuplot `plot` command over the clauses, a clause per line.
std::string PlotList(const std::vector<std::string>& clauses);

}  // namespace deb::report
