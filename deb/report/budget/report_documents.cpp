#include "deb/report/budget/report_documents.h"

#include <functional>
#include <sstream>

#include "deb/report/budget/interactive_figures.h"
#include "deb/report/budget/requirement_lines.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr const char* kCss = R"(
:root { --ink: #1a1a1a; --muted: #5c5c5c; --line: #d9d9d9; --fail: #b2182b; }
body { font-family: "DejaVu Sans", system-ui, "Segoe UI", Helvetica, Arial, sans-serif; color: var(--ink);
       max-width: 1240px; margin: 2rem auto; padding: 0 1.5rem; line-height: 1.45; }
h1 { font-size: 1.7rem; margin-bottom: 0.2rem; }
h2 { border-bottom: 1px solid var(--line); padding-bottom: 0.2rem; margin-top: 2.4rem; }
h3 { margin-top: 1.6rem; }
p.lead { color: var(--muted); margin-top: 0; }
nav { font-size: 0.92rem; margin: 1rem 0; }
nav a { margin-right: 1rem; }
table { border-collapse: collapse; margin: 0.6rem 0 1.4rem; font-size: 0.92rem; }
caption { text-align: left; font-weight: bold; padding: 0.3rem 0; }
th, td { border-bottom: 1px solid var(--line); padding: 0.25rem 0.7rem; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.notes { color: var(--muted); font-size: 0.85rem; padding-top: 0.3rem; }
table.facts td:first-child { color: var(--muted); white-space: nowrap; }
table.facts td { font-family: "DejaVu Sans Mono", monospace; font-size: 0.88rem; }
strong.fail, td strong { color: inherit; }
.fail { color: var(--fail); font-weight: bold; }
figure { margin: 1rem 0 2.2rem; }
figure img { max-width: 100%; height: auto; border: 1px solid var(--line); }
figcaption { color: var(--muted); font-size: 0.9rem; }
ul.files { font-family: "DejaVu Sans Mono", monospace; font-size: 0.88rem; }
@media print { nav { display: none; } figure { break-inside: avoid; } }
)";

std::string Href(const std::string& path) {
  std::string out;
  for (char c : path) out += c == ' ' ? std::string("%20") : c == '"' ? std::string("%22") : std::string(1, c);
  return out;
}

// " Files: <a>NAME.png</a>, <a>NAME.csv</a>." for the plot files of the same
// figure, if written (an image for slides, the data to plot elsewhere).
std::string FileLinks(const std::vector<Plot>& plots, const std::string& ext,
                      const std::function<bool(const Plot&)>& same) {
  std::string s;
  const auto link = [&](const std::string& file) {
    s += std::string(s.empty() ? " Files: " : ", ") + "<a href=\"" + Href("plots/" + file) + "\">" +
         HtmlEscape(file) + "</a>";
  };
  for (const Plot& p : plots)
    if (same(p)) {
      if (!ext.empty()) link(p.name + "." + ext);
      link(p.name + ".csv");
    }
  return s.empty() ? s : s + ".";
}

std::string DataLinks(const DocumentInputs& in, PlotKind kind, int output) {
  return FileLinks(in.plots, in.image_extension,
                   [&](const Plot& p) { return p.kind == kind && p.output == output; });
}

std::string MarkdownFigure(const Plot& p, const std::string& ext) {
  std::string s;
  if (!ext.empty()) s += "![" + p.caption + "](" + Href("plots/" + p.name + "." + ext) + ")\n\n";
  s += "*" + p.caption + "* Data: [" + p.name + ".csv](" + Href("plots/" + p.name + ".csv") + "), script: [" + p.name +
       ".gp](" + Href("plots/" + p.name + ".gp") + ").\n\n";
  return s;
}

std::string OutputLine(const OutputResult& o) {
  std::string s = "RMS " + Sig(o.rms(), 4) + " " + UnitText(o.unit);
  if (o.rms_max)
    s += "; requirement " + Short(*o.rms_max) + " " + UnitText(o.unit) + ": " + (o.pass() ? "pass" : "FAIL") +
         " (margin " + Sig(*o.rms_max - o.rms(), 4) + " " + UnitText(o.unit) + ")";
  return s + ". Signal " + o.signal + ".";
}

// The verdict at the head of index.html: a line per requirement, green
// where it is met and red with the guidance where it fails; an output
// without requirements in grey. The banner's class says whether every
// output meets its requirements (pass), one fails (fail), or none has any.
std::string VerdictBanner(const BudgetResult& result) {
  bool all_pass = true, any_required = false;
  std::string lines;
  for (const OutputResult& o : result.outputs) {
    const std::string unit = UnitText(o.unit);
    all_pass = all_pass && o.AllPass();
    const std::vector<RequirementLine> required = RequirementLines(o);
    any_required = any_required || !required.empty();
    if (required.empty()) {
      lines += "<p class=\"none\"><strong>no requirement</strong> " + HtmlEscape(o.name) + ": RMS " +
               HtmlEscape(Sig(o.rms(), 4) + " " + unit) + ".</p>\n";
      continue;
    }
    std::string fix = GuidanceText(o, result.grid);
    for (const RequirementLine& l : required) {
      lines += std::string("<p class=\"") + (l.pass ? "pass" : "fail") + "\"><strong>" + (l.pass ? "PASS" : "FAIL") +
               "</strong> " + HtmlEscape(o.name) + (l.overall() ? "" : ", " + HtmlEscape(l.scope)) + ": RMS " +
               HtmlEscape(Sig(l.rms, 4) + " " + unit + " (requirement " + Short(l.rms_max) + " " + unit + ").");
      if (!l.pass && !fix.empty()) lines += " " + HtmlEscape(fix);
      if (!l.pass) fix.clear();  // once per output
      lines += "</p>\n";
    }
  }
  const char* verdict = !all_pass ? "fail" : any_required ? "pass" : "none";
  return std::string("<div class=\"verdict ") + verdict + "\" id=\"verdict\">\n" + lines + "</div>\n";
}

template <typename Fn>
void ForPlots(const std::vector<Plot>& plots, PlotKind kind, int output, Fn fn) {
  for (const Plot& p : plots)
    if (p.kind == kind && (output < 0 || p.output == output)) fn(p);
}

}  // namespace

std::string OutputAnchor(const std::string& output_name) { return "output-" + FileStem(output_name); }

std::string IndexHtml(const DocumentInputs& in) {
  const BudgetOutline& budget = in.result->outline;
  const BudgetResult& result = *in.result;
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<title>deb report: " << HtmlEscape(budget.name) << "</title>\n<style>" << kCss << FigureCss()
    << "</style>\n</head>\n<body>\n";
  s << "<h1>Dynamic error budget: " << HtmlEscape(budget.name) << "</h1>\n";
  if (!budget.description.empty()) s << "<p class=\"lead\">" << HtmlEscape(budget.description) << "</p>\n";
  s << VerdictBanner(result);
  for (const std::string& w : MeasurementWarnings(result, in.digits))
    s << "<p class=\"fail\">" << HtmlEscape(w) << "</p>\n";
  s << "<noscript><p class=\"noscript\">The figures of this page are drawn by the JavaScript it carries, which "
       "is disabled: the tables below hold the figures' numbers";
  if (in.pdf) s << ", and <a href=\"report.pdf\">report.pdf</a> every plot";
  s << ".</p></noscript>\n";
  s << "<nav><a href=\"#summary\">Summary</a>";
  for (const OutputResult& o : result.outputs)
    s << "<a href=\"#" << HtmlEscape(OutputAnchor(o.name)) << "\">" << HtmlEscape(o.name) << "</a>";
  s << "<a href=\"#paths\">Paths</a><a href=\"#files\">Files</a></nav>\n";

  s << "<h2 id=\"summary\">Summary</h2>\n<table class=\"facts\">\n";
  for (const ReportFact& f : in.facts.items)
    s << "<tr><td>" << HtmlEscape(f.label) << "</td><td>" << HtmlEscape(f.value) << "</td></tr>\n";
  s << "</table>\n" << ToHtml(SummaryTable(result, in.digits));
  if (const Table parameters = ParametersTable(result.outline, in.digits); !parameters.rows.empty())
    s << ToHtml(parameters);
  if (result.covariance) s << ToHtml(CovarianceTable(*result.covariance, in.digits));
  s << "<h3>Conventions</h3>\n<ul>\n";
  for (const auto& c : in.facts.conventions) s << "<li>" << HtmlEscape(c) << "</li>\n";
  s << "</ul>\n";
  if (!result.warnings.empty()) {
    s << "<h3>Warnings</h3>\n<ul>\n";
    for (const auto& w : result.warnings) s << "<li>" << HtmlEscape(w) << "</li>\n";
    s << "</ul>\n";
  }

  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    const OutputResult& out = result.outputs[o];
    s << "<h2 id=\"" << HtmlEscape(OutputAnchor(out.name)) << "\">Output " << HtmlEscape(out.name) << " ["
      << HtmlEscape(UnitText(out.unit)) << "]</h2>\n<p" << (out.pass() ? "" : " class=\"fail\"") << ">"
      << HtmlEscape(OutputLine(out)) << "</p>\n";
    if (const std::string fix = GuidanceText(out, result.grid); !fix.empty())
      s << "<p class=\"guidance\"><strong>" << HtmlEscape(fix) << "</strong></p>\n";
    s << ToHtml(ContributorTable(out, in.digits));
    if (const Table channels = ChannelTable(out, in.digits); !channels.rows.empty()) s << ToHtml(channels);
    if (const Table modes = ModeTable(out); !modes.rows.empty()) s << ToHtml(modes);
    if (const Table groups = GroupTable(out, in.digits); !groups.rows.empty()) s << ToHtml(groups);
    if (const Table refs = ReferenceTable(out, in.digits); !refs.rows.empty()) s << ToHtml(refs);
    const std::string req =
        out.rms_max ? " The dashed red line is the requirement, " + Short(*out.rms_max) + " " + UnitText(out.unit) +
                          " RMS, as a variance." : "";
    const int oi = static_cast<int>(o);
    // What the CPS and PSD show: the items of the PNG figures (GroupLevel).
    const PlotLevel level = GroupLevel(out, result.grid, "");
    const std::string cross = out.rms_max ? " The dotted line marks where the cumulative RMS reaches it." : "";
    s << FigureElement("cps", o,
                       HtmlEscape("Cumulative power spectrum of " + out.name + ", " + level.items +
                                  " stacked: the height at f is the variance from the lowest frequency to f; the "
                                  "right axis reads it as RMS." + req + cross) +
                           DataLinks(in, PlotKind::kCps, oi))
      << FigureElement(in.asd ? "asd" : "psd", o,
                       HtmlEscape("Power spectral density of " + out.name + " per " + level.item +
                                  " and in total (black); zooming here zooms the CPS above.") +
                           DataLinks(in, PlotKind::kSpectrum, oi));
    s << "<h3>Frequency bands</h3>\n" << ToHtml(BandTable(out, in.digits));
    s << FigureElement("bands", o,
                       HtmlEscape("Variance of " + out.name + " per frequency band, contributors stacked (variances add up; "
                                  "the table above gives their RMS).") +
                           DataLinks(in, PlotKind::kBands, oi));
  }

  s << "<h2 id=\"paths\">Paths</h2>\n<p>Magnitude of each contributor's transfer to each output, per source channel, "
       "with the unit conversions and weightings the budget applies.</p>\n";
  for (std::size_t c = 0, i = 0; c < budget.contributors.size(); ++c)
    for (std::size_t o = 0; o < result.outputs.size(); ++o, ++i) {
      const Contributor& con = budget.contributors[c];
      s << "<h3>" << HtmlEscape(con.name + " → " + result.outputs[o].name) << "</h3>\n";
      s << FigureElement("path", i,
                         HtmlEscape("Magnitude of the transfer from " + con.name + " (source " + con.source + ", path " +
                                    con.path + ") to " + result.outputs[o].name + ", per source channel.") +
                             FileLinks(in.plots, in.image_extension, [&](const Plot& p) {
                               return p.kind == PlotKind::kPath &&
                                      p.name == "path_" + FileStem(con.name) + "_to_" + FileStem(result.outputs[o].name);
                             }));
    }

  s << "<h2 id=\"files\">Files</h2>\n<ul class=\"files\">\n";
  if (in.pdf) s << "<li><a href=\"report.pdf\">report.pdf</a> — the typeset report: verdict, contents, tables and every plot</li>\n";
  s << "<li><a href=\"report.md\">report.md</a> — these tables as Markdown</li>\n";
  for (const auto& f : in.data_files) s << "<li><a href=\"" << Href(f) << "\">" << HtmlEscape(f) << "</a></li>\n";
  if (const std::string overview = FileLinks(in.plots, in.image_extension,
                                             [](const Plot& p) { return p.kind == PlotKind::kOverview; });
      !overview.empty())
    s << "<li>RMS per output and contributor against the requirements." << overview << "</li>\n";
  if (!in.plots.empty())  // written with the plots' files
    s << "<li><a href=\"plots/colours.csv\">plots/colours.csv</a> — the colour and dash pattern of each "
         "contributor</li>\n";
  s << "</ul>\n<p class=\"lead\">Written by deb " << DEB_VERSION << ". Figures drawn with dygraphs "
       "(MIT licence, inlined below with its notice).</p>\n"
    << FigureScripts(FigureDataJson(result)) << "</body>\n</html>\n";
  return s.str();
}

std::string ReportMarkdown(const DocumentInputs& in) {
  const BudgetOutline& budget = in.result->outline;
  const BudgetResult& result = *in.result;
  std::ostringstream s;
  s << "# Dynamic error budget: " << budget.name << "\n\n";
  if (!budget.description.empty()) s << budget.description << "\n\n";
  s << "## Summary\n\n| | |\n| --- | --- |\n";
  for (const ReportFact& f : in.facts.items) s << "| " << f.label << " | `" << f.value << "` |\n";
  s << "\n" << ToMarkdown(SummaryTable(result, in.digits)) << "\n";
  for (const std::string& w : MeasurementWarnings(result, in.digits)) s << "**" << w << "**\n\n";
  if (const Table parameters = ParametersTable(budget, in.digits); !parameters.rows.empty())
    s << "### " << parameters.title << "\n\n" << ToMarkdown(parameters) << "\n";
  if (result.covariance) {
    const Table covariance = CovarianceTable(*result.covariance, in.digits);
    s << "### " << covariance.title << "\n\n" << ToMarkdown(covariance) << "\n";
  }
  s << "### Conventions\n\n";
  for (const auto& c : in.facts.conventions) s << "- " << c << "\n";
  if (!result.warnings.empty()) {
    s << "\n### Warnings\n\n";
    for (const auto& w : result.warnings) s << "- " << w << "\n";
  }
  s << "\n## Overview\n\n";
  ForPlots(in.plots, PlotKind::kOverview, -1, [&](const Plot& p) { s << MarkdownFigure(p, in.image_extension); });
  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    const OutputResult& out = result.outputs[o];
    const int oi = static_cast<int>(o);
    s << "## Output " << out.name << " [" << UnitText(out.unit) << "]\n\n" << OutputLine(out) << "\n\n";
    if (const std::string fix = GuidanceText(out, result.grid); !fix.empty()) s << "**" << fix << "**\n\n";
    s << ToMarkdown(ContributorTable(out, in.digits)) << "\n";
    if (const Table channels = ChannelTable(out, in.digits); !channels.rows.empty()) s << ToMarkdown(channels) << "\n";
    if (const Table modes = ModeTable(out); !modes.rows.empty()) s << ToMarkdown(modes) << "\n";
    if (const Table groups = GroupTable(out, in.digits); !groups.rows.empty()) s << ToMarkdown(groups) << "\n";
    if (const Table refs = ReferenceTable(out, in.digits); !refs.rows.empty())
      s << ToMarkdown(refs) << "\n";
    for (PlotKind k : {PlotKind::kCps, PlotKind::kReverseCps, PlotKind::kSpectrum})
      ForPlots(in.plots, k, oi, [&](const Plot& p) { s << MarkdownFigure(p, in.image_extension); });
    s << "### Frequency bands\n\n" << ToMarkdown(BandTable(out, in.digits)) << "\n";
    ForPlots(in.plots, PlotKind::kBands, oi, [&](const Plot& p) { s << MarkdownFigure(p, in.image_extension); });
  }
  s << "## Paths\n\n";
  ForPlots(in.plots, PlotKind::kPath, -1, [&](const Plot& p) { s << MarkdownFigure(p, in.image_extension); });
  s << "## Files\n\n";
  if (in.pdf) s << "- [report.pdf](report.pdf): the typeset report: verdict, contents, tables and every plot\n";
  s << "- [index.html](index.html): this report for a browser\n";
  for (const auto& f : in.data_files) s << "- [" << f << "](" << Href(f) << ")\n";
  if (!in.plots.empty()) s << "- [plots/colours.csv](plots/colours.csv): the colour and dash pattern of each contributor\n";
  return s.str();
}

}  // namespace deb::report
