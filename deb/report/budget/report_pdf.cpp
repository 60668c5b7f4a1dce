#include "deb/report/budget/report_pdf.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "deb/report/budget/band_text.h"
#include "deb/report/budget/requirement_lines.h"
#include "deb/version.h"

namespace deb::report {

namespace fs = std::filesystem;
namespace {

bool Fails(const OutputResult& o) {
  bool fails = o.rms_max && !o.pass();
  for (const BandRequirementResult& b : o.band_requirements) fails = fails || !b.pass();
  return fails;
}

// The heading of an output's section, which its row of the verdict links to.
std::string SectionTitle(const OutputResult& o) { return "Output " + o.name; }

bool HasRequirement(const OutputResult& o) { return o.rms_max || !o.band_requirements.empty(); }

// PASS in green or FAIL in red.
PdfCell Verdict(bool pass) {
  PdfCell c{pass ? "PASS" : "FAIL", true, !pass};
  c.good = pass;
  return c;
}

// An output's verdict, a line per requirement: "FAIL: RMS 12.3 nm against a
// limit of 5 nm (exceeded)." then "PASS: 1–10 Hz: RMS 2.1 nm against 3 nm
// (met).", each red only where it fails.
std::vector<std::pair<std::string, bool>> VerdictLines(const OutputResult& o) {
  const std::string unit = UnitText(o.unit);
  if (!HasRequirement(o)) return {{"No requirement: RMS " + Sig(o.rms(), 4) + " " + unit + ".", false}};
  std::vector<std::pair<std::string, bool>> lines;
  for (const RequirementLine& l : RequirementLines(o))
    lines.emplace_back(std::string(l.pass ? "PASS" : "FAIL") + ": " + RequirementSentence(l, unit) + ".", !l.pass);
  return lines;
}

// The Bode figures of an output's paths, listed rather than drawn: a
// budget's path catalogue can fill more pages than its results (wafer_stage:
// 15 figures). index.html draws each, and plots/ holds its image, data and
// script.
std::string PathFiguresTitle() {
  return "Bode figures of the paths: drawn in index.html; image, data and script in plots/";
}

PdfTable PathFigures(const std::vector<const Plot*>& plots) {
  PdfTable t;
  t.header = {"path (inputs) to output, used by", "plots/ file stem (image, .csv, .gp)"};
  t.numeric = {false, false};
  for (const Plot* p : plots) t.rows.push_back({{p->label.empty() ? p->caption : p->label}, {p->name}});
  return t;
}

// Room an output's section needs to start below the previous one rather than on a new page.
constexpr double kOutputSectionRoomPt = 200.0;
// Room the table of contents (a line per section) needs to follow page 1's tables.
constexpr double kContentsRoomPt = 140.0;

// Plots of an output in reading order: CPS, reverse CPS, spectrum, bands.
int KindOrder(PlotKind k) {
  switch (k) {
    case PlotKind::kOverview: return 0;
    case PlotKind::kCps: return 1;
    case PlotKind::kReverseCps: return 2;
    case PlotKind::kSpectrum: return 3;
    case PlotKind::kBands: return 4;
    case PlotKind::kPath: return 5;
  }
  return 6;
}

// The covariance of the outputs the budget's `covariance:` lists, the table
// index.html and report.md show below their summary; nothing without one.
void AddCovarianceTable(const BudgetResult& result, int digits, std::vector<PdfBlock>* blocks) {
  if (!result.covariance) return;
  const Table covariance = CovarianceTable(*result.covariance, digits);
  blocks->push_back(TableBlock(covariance.title, TypesetTable(covariance)));
}

}  // namespace

int PdfFigureHeightPx(const Plot& p) {
  return p.pdf_height_px > 0 ? p.pdf_height_px : p.kind == PlotKind::kOverview ? 600 : 420;
}

PdfBlock FigureOfPlot(const Plot& p, const std::string& figure_dir) {
  PdfBlock b = Figure((fs::path(figure_dir) / (p.name + ".svg")).string(), p.caption);
  b.width_px = kPdfFigureWidthPx;
  b.height_px = PdfFigureHeightPx(p);
  return b;
}

std::map<std::string, int> FittedFigureHeights(PdfDocumentSpec spec) {
  for (PdfBlock& b : spec.blocks)
    if (b.kind == PdfBlockKind::kFigure) b.min_height_px = (2 * b.height_px + 2) / 3;
  const std::vector<int> heights = FittedFigureHeightsPx(spec, PlanPdfDocument(spec));
  std::map<std::string, int> by_name;
  std::size_t i = 0;
  for (const PdfBlock& b : spec.blocks)
    if (b.kind == PdfBlockKind::kFigure) by_name[fs::path(b.svg_file).stem().string()] = heights[i++];
  return by_name;
}

std::string PdfFigureTerminal(const Plot& p) {
  // Placed across the text width (A4 less two 18 mm margins, 481 pt), a
  // 662 px wide SVG is scaled by 0.727: the plots' base font of 11 px is set
  // at 8 pt and their titles (14 px) at 10 pt; the fonts the plot scripts ask
  // for keep their proportions to each other and to the canvas. linewidth
  // 2.1 puts a line of width 1 at 1.53 pt on paper (the thinnest data line,
  // 1.1, at 1.68 pt; only the grid is lighter). Two fit on a page; the
  // overview's panels get most of one, unless the plot asks for its height.
  const int height = PdfFigureHeightPx(p);
  return "set terminal svg enhanced size " + std::to_string(kPdfFigureWidthPx) + "," + std::to_string(height) +
         " font 'DejaVu Sans,11' linewidth 2.1 background '#ffffff'\n" + kPdfFigureVariable + " = 1\n" +
         kPdfHeightVariable + " = " + std::to_string(height) + "\n";
}

std::string PdfFigureCommands(const Plot& p) {
  return DrawCommands(PdfFigureTerminal(p), std::string(kPdfFigureDir) + "/" + p.name + ".svg", p.name + ".gp");
}

PdfTable TypesetTable(const Table& given, std::size_t min_note_chars) {
  // Long text said once, below the table (WithNotesBelow): the note column
  // holds marks only and its width goes to the names and numbers rather
  // than to rows five lines tall.
  PdfTable t;
  const Table table = WithNotesBelow(given, &t.footnotes, min_note_chars);
  t.footnotes.insert(t.footnotes.end(), given.notes.begin(), given.notes.end());
  t.header = table.header;
  t.numeric = table.numeric;
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    std::vector<PdfCell> cells;
    for (std::size_t c = 0; c < table.rows[r].size(); ++c) {
      const std::string& text = table.rows[r][c];
      PdfCell cell{text, r < table.emphasis.size() && c < table.emphasis[r].size() && table.emphasis[r][c], false};
      // A number with words after it ("1.83×, each of top 3"): the words on
      // a line of their own, so that they do not widen the column.
      if (c < table.numeric.size() && table.numeric[c])
        if (const std::size_t comma = text.find(", "); comma != std::string::npos)
          cell.text = text.substr(0, comma) + "\n" + text.substr(comma + 2);
      cell.alert = text == "FAIL";
      cell.bold = cell.bold || cell.alert;
      cells.push_back(cell);
    }
    t.rows.push_back(std::move(cells));
  }
  return t;
}

PdfTable VerdictTable(const BudgetResult& result) {
  PdfTable t;
  t.boxed = true;
  t.header = {"output", "requirement", "value", "verdict", "what would meet it"};
  t.numeric = {false, false, false, false, false};
  bool any_fails = false;
  for (const OutputResult& o : result.outputs) any_fails = any_fails || Fails(o);
  // A row per requirement line, the output named on its first; what would
  // meet a failing output's requirements beside its first line.
  for (const OutputResult& o : result.outputs) {
    const std::string unit = UnitText(o.unit);
    const std::string guidance = Fails(o) ? GuidanceText(o, result.grid) : "";
    const PdfCell name{o.name, true, false, SectionTitle(o)};
    if (!HasRequirement(o)) {
      t.rows.push_back({name, {"none"}, {Sig(o.rms(), 4) + " " + unit}, {"–", true, false}, {"–"}});
      if (!any_fails) t.rows.back().pop_back();  // nothing to meet: no column for it
      continue;
    }
    const std::vector<RequirementLine> lines = RequirementLines(o);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const RequirementLine& l = lines[i];
      const std::string requirement =
          (l.overall() ? "" : l.scope + ": ") + "RMS ≤ " + Short(l.rms_max) + " " + unit;
      t.rows.push_back({i == 0 ? name : PdfCell{""}, {requirement}, {Sig(l.rms, 4) + " " + unit},
                        Verdict(l.pass),
                        {i == 0 && !guidance.empty() ? guidance : "–"}});
      if (!any_fails) t.rows.back().pop_back();
    }
  }
  if (!any_fails) {
    t.header.pop_back();
    t.numeric.pop_back();
  }
  return t;
}

bool DrawnInPdf(const Plot& p) { return !(p.kind == PlotKind::kPath && p.output >= 0); }

PdfDocumentSpec ReportPdfSpec(const ReportPdfInputs& in) {
  const BudgetOutline& budget = in.result->outline;
  const BudgetResult& result = *in.result;
  PdfDocumentSpec s;
  s.title = budget.name + ": dynamic error budget";
  s.subject = budget.description;
  s.create_date = in.create_date;
  s.footer = "deb " + std::string(DEB_VERSION) + " · " + budget.name +
             (in.sha256.empty() ? "" : " · SHA-256 " + in.sha256.substr(0, 12));
  auto& b = s.blocks;

  // Page 1: what, from which file, and the verdict.
  b.push_back(Heading(0, budget.name));
  if (!budget.description.empty()) b.push_back(Paragraph(budget.description, 10.5));
  PdfTable facts;
  facts.numeric = {false, false};
  for (const ReportFact& f : in.facts.items)
    if (!f.shown_elsewhere_on_pdf_title_page) facts.rows.push_back({{f.label, true, false}, {f.value}});
  b.push_back(TableBlock("", facts));
  b.push_back(TableBlock("Verdict", VerdictTable(result)));
  for (const std::string& w : MeasurementWarnings(result, in.digits)) b.push_back(Paragraph(w, 9.5, true, true));
  if (const Table parameters = ParametersTable(budget, in.digits); !parameters.rows.empty())
    b.push_back(TableBlock(parameters.title, TypesetTable(parameters)));
  if (const std::size_t n = result.warnings.size(); n > 0)
    b.push_back(Paragraph("The evaluation raised " + std::to_string(n) + (n == 1 ? " warning" : " warnings") +
                              ": see Warnings and notes.",
                          9.5, true));
  b.push_back(PageBreak(kContentsRoomPt));  // the contents below a short first page
  b.push_back(Heading(1, "Contents"));
  b.push_back(Contents());
  b.push_back(PageBreak(kOutputSectionRoomPt));  // the overview below a short table of contents

  const auto figure = [&](const Plot& p) { b.push_back(FigureOfPlot(p, in.figure_dir)); };
  const std::vector<Plot> none;
  const std::vector<Plot>& plots = in.plots ? *in.plots : none;

  b.push_back(Heading(1, "Overview"));
  b.push_back(TableBlock("Summary", TypesetTable(SummaryTable(result, in.digits))));
  AddCovarianceTable(result, in.digits, &b);
  for (const Plot& p : plots)
    if (p.output < 0 && p.kind != PlotKind::kPath) figure(p);

  std::vector<const Plot*> all_path_plots;  // listed after the loops, drawn in index.html
  for (std::size_t i = 0; i < result.outputs.size(); ++i) {
    const OutputResult& o = result.outputs[i];
    // A new page unless kOutputSectionRoomPt are left: the heading, the verdict and the table's first rows fit there.
    b.push_back(PageBreak(kOutputSectionRoomPt));
    b.push_back(Heading(1, SectionTitle(o)));
    for (const auto& [line, fails] : VerdictLines(o))
      b.push_back(Paragraph(line, 10.0, true, fails, HasRequirement(o) && !fails));
    if (Fails(o))
      if (const std::string g = GuidanceText(o, result.grid); !g.empty()) b.push_back(Paragraph(g, 9.5));
    const Table contributors = ContributorTable(o, in.digits);
    b.push_back(TableBlock(contributors.title, TypesetTable(contributors)));
    if (const Table groups = GroupTable(o, in.digits); !groups.rows.empty())
      b.push_back(TableBlock(groups.title, TypesetTable(groups)));
    if (const Table refs = ReferenceTable(o, in.digits); !refs.rows.empty())
      b.push_back(TableBlock(refs.title, TypesetTable(refs)));
    if (const Table channels = ChannelTable(o, in.digits); !channels.rows.empty())
      b.push_back(TableBlock(channels.title, TypesetTable(channels)));
    if (const Table modes = ModeTable(o); !modes.rows.empty())
      b.push_back(TableBlock(modes.title, TypesetTable(modes)));
    // The tables first (the band table fills the page the output's tables
    // began), then its figures in reading order; its path figures are
    // listed in the section Paths.
    std::vector<const Plot*> mine, path_plots;
    for (const Plot& p : plots)
      if (p.output == static_cast<int>(i)) (DrawnInPdf(p) ? mine : path_plots).push_back(&p);
    std::stable_sort(mine.begin(), mine.end(),
                     [](const Plot* a, const Plot* z) { return KindOrder(a->kind) < KindOrder(z->kind); });
    b.push_back(Heading(2, "Bands of " + o.name));
    const Table band = BandTable(o, in.digits);
    b.push_back(TableBlock(band.title, TypesetTable(band)));
    if (!mine.empty()) b.push_back(Heading(2, "Figures of " + o.name));
    for (const Plot* p : mine) figure(*p);
    all_path_plots.insert(all_path_plots.end(), path_plots.begin(), path_plots.end());
  }

  // Loop plots belong to no output: a section of their own.
  bool loops = false;
  for (const Plot& p : plots) {
    if (p.output >= 0 || p.kind != PlotKind::kPath) continue;
    if (!loops) {
      b.push_back(PageBreak(kOutputSectionRoomPt));
      b.push_back(Heading(1, "Feedback loops"));
      loops = true;
    }
    figure(p);
  }

  if (!all_path_plots.empty()) {
    b.push_back(PageBreak(kOutputSectionRoomPt));
    b.push_back(Heading(1, "Paths"));
    b.push_back(TableBlock(PathFiguresTitle(), PathFigures(all_path_plots)));
  }
  b.push_back(PageBreak(kOutputSectionRoomPt));
  b.push_back(Heading(1, "Warnings and notes"));
  if (result.warnings.empty()) b.push_back(Paragraph("The evaluation raised no warning."));
  for (const std::string& w : result.warnings) b.push_back(Bullet(w));
  b.push_back(Heading(1, "Conventions"));
  for (const std::string& c : in.facts.conventions) b.push_back(Bullet(c));
  return s;
}

}  // namespace deb::report
