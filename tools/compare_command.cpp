#include "tools/compare_command.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "deb/core/output_dir.h"
#include "deb/budget/comparison.h"
#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/parallel.h"
#include "deb/io/budget_yaml.h"
#include "deb/io/comparison_files.h"
#include "deb/io/result_writer.h"
#include "deb/report/overlay_plots.h"
#include "deb/report/plot.h"
#include "deb/report/report_tables.h"

namespace deb::tools {
namespace {

namespace fs = std::filesystem;

struct CompareSettings {
  std::vector<std::string> inputs;
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool force = false;  // --force: replace an output directory deb did not write
  bool plots = true;
};

// Figures, and the full result where the input was a budget (for plots).
struct Loaded {
  ResultFigures figures;
  std::optional<BudgetResult> result;
};

CompareSettings& Settings() {
  static CompareSettings settings;
  return settings;
}

// A budget file is evaluated; a directory (or a summary.json) is read.
Loaded Load(const std::string& input, int threads) {
  const fs::path p(input);
  if (fs::is_directory(p)) {
    const fs::path summary = p / "summary.json";
    if (!fs::exists(summary))
      throw InputError(input + ": a directory given to compare must hold summary.json (written by deb run)");
    return {ReadSummaryFigures(summary.string(), p.filename().empty() ? p.parent_path().filename().string()
                                                                      : p.filename().string()),
            std::nullopt};
  }
  if (p.extension() == ".json") {
    const std::string dir = fs::absolute(p).parent_path().filename().string();
    return {ReadSummaryFigures(input, dir.empty() ? p.stem().string() : dir), std::nullopt};
  }
  const Budget budget = LoadBudgetFile(input);
  EngineOptions options;
  options.threads = threads;
  BudgetResult result = Evaluate(budget, options);
  ResultFigures figures = FiguresOf(budget.name, result);
  return {std::move(figures), std::move(result)};
}

std::string Ratio(const ComparedFigure& f) { return f.ratio ? report::Sig(*f.ratio, 4) : "–"; }

// The tables of a comparison: one per output, then the largest changes.
std::vector<report::Table> Tables(const Comparison& cmp) {
  std::vector<report::Table> tables;
  std::string current;
  for (const ComparedFigure& f : cmp.figures) {
    if (tables.empty() || f.output != current) {
      current = f.output;
      report::Table t;
      t.title = f.output + " [" + report::UnitText(f.unit) + "]";
      t.header = {"contributor", "band", "A: " + cmp.label_a, "B: " + cmp.label_b, "B − A", "B / A"};
      t.numeric = {false, false, true, true, true, true};
      tables.push_back(t);
    }
    report::Table& t = tables.back();
    t.rows.push_back({f.contributor, f.band.empty() ? "whole grid" : f.band, report::Sig(f.rms_a, 4),
                      report::Sig(f.rms_b, 4), report::Sig(f.difference, 4), Ratio(f)});
    t.emphasis.push_back(std::vector<bool>(6, f.contributor == "total" && f.band.empty()));
  }
  report::Table largest;
  largest.title = "Contributors that changed most";
  largest.header = {"output", "contributor", "A", "B", "B / A", "variance change / total"};
  largest.numeric = {false, false, true, true, true, true};
  for (const ComparedFigure& f : cmp.LargestChanges())
    largest.rows.push_back({f.output, f.contributor, report::Sig(f.rms_a, 4), report::Sig(f.rms_b, 4), Ratio(f),
                            report::Sig(100.0 * f.variance_change_of_total, 3) + " %"});
  tables.push_back(largest);
  return tables;
}

std::string Lead() {
  return "RMS per output, contributor and band; difference B − A in the output's unit; ratio B / A.";
}

std::string Markdown(const Comparison& cmp, const std::vector<report::Plot>& plots) {
  std::ostringstream md;
  md << "# Comparison: " << cmp.label_a << " (A) vs " << cmp.label_b << " (B)\n\n" << Lead() << "\n\n";
  for (const report::Table& t : Tables(cmp)) md << "## " << t.title << "\n\n" << report::ToMarkdown(t) << "\n";
  for (const report::Plot& p : plots)
    md << "![" << p.caption << "](plots/" << p.name << ".png)\n\n" << p.caption << "\n\n";
  if (!cmp.unmatched.empty()) {
    md << "## Not compared\n\n";
    for (const std::string& s : cmp.unmatched) md << "- " << s << "\n";
  }
  return md.str();
}

// One self-contained page (the plots are files beside it).
std::string Html(const Comparison& cmp, const std::vector<report::Plot>& plots) {
  using report::HtmlEscape;
  std::ostringstream h;
  const std::string title = "Comparison: " + cmp.label_a + " (A) vs " + cmp.label_b + " (B)";
  h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << HtmlEscape(title)
    << "</title>\n<style>body{font-family:'DejaVu Sans',sans-serif;max-width:1240px;margin:2rem auto;padding:0 1.5rem}"
       "table{border-collapse:collapse;margin:.6rem 0 1.4rem;font-size:.92rem}th,td{border-bottom:1px solid #ddd;"
       "padding:.2rem .6rem}td.num{text-align:right;font-variant-numeric:tabular-nums}img{max-width:100%}</style>\n"
       "</head>\n<body>\n<h1>"
    << HtmlEscape(title) << "</h1>\n<p>" << HtmlEscape(Lead()) << "</p>\n";
  for (const report::Table& t : Tables(cmp)) h << report::ToHtml(t);  // the caption titles it
  for (const report::Plot& p : plots)
    h << "<figure><img src=\"plots/" << HtmlEscape(p.name) << ".png\" alt=\"" << HtmlEscape(p.caption)
      << "\"><figcaption>" << HtmlEscape(p.caption) << "</figcaption></figure>\n";
  if (!cmp.unmatched.empty()) {
    h << "<h2>Not compared</h2>\n<ul>\n";
    for (const std::string& s : cmp.unmatched) h << "<li>" << HtmlEscape(s) << "</li>\n";
    h << "</ul>\n";
  }
  h << "</body>\n</html>\n";
  return h.str();
}

std::string Safe(const std::string& label) {
  std::string s = label;
  for (char& ch : s)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.')) ch = '_';
  return s;
}

void WriteComparison(const Comparison& cmp, const std::vector<report::Plot>& plots, const std::string& out_dir,
                     bool force, int threads) {
  ReplaceOptions replace;
  replace.force = force;
  ReplaceDirectory(out_dir, [&](const std::string& dir) {
    if (!plots.empty()) {
      fs::create_directories(fs::path(dir) / "plots");
      report::WritePlotsAsPng(plots, (fs::path(dir) / "plots").string(), threads);
    }
    const std::vector<std::pair<std::string, std::string>> files = {{"compare.json", ComparisonJson(cmp)},
                                                                    {"compare.md", Markdown(cmp, plots)},
                                                                    {"compare.html", Html(cmp, plots)},
                                                                    {"compare.csv", ComparisonCsv(cmp)}};
    for (const auto& [name, text] : files) WriteTextFile((fs::path(dir) / name).string(), text);
  }, replace);
}

}  // namespace

CLI::App* AddCompareCommand(CLI::App& app) {
  CompareSettings& s = Settings();
  CLI::App* c = app.add_subcommand(
      "compare", "Compare budgets or result directories: RMS per output, contributor and band, B - A and B / A");
  c->add_option("inputs", s.inputs, "Budget YAML files or result directories (summary.json); the first is A")
      ->required()
      ->expected(2, 1000)
      ->check(CLI::ExistingPath);
  c->add_option("--out,-o", s.out_dir, "Report directory, for two inputs (default: reports/compare_<A>_vs_<B>)");
  c->add_option("--threads,-j", s.threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; },
                       "No overlay plots (drawn only when both inputs are budgets; need gnuplot)");
  return c;
}

int RunCompareCommand(const CLI::App& /*compare*/) {
  const CompareSettings& s = Settings();
  if (!s.out_dir.empty() && s.inputs.size() != 2)
    throw InputError("--out names one directory: give exactly two inputs, or leave --out out");
  // All or nothing: every input is loaded (a budget evaluated) and every
  // comparison built before the first directory is written.
  // One job per input (loading and evaluating it); an error is the first
  // input's that fails, as in a serial loop.
  std::vector<Loaded> loaded(s.inputs.size());
  ParallelForEach(loaded.size(), [&](std::size_t i) { loaded[i] = Load(s.inputs[i], s.threads); }, s.threads);
  struct Pending {
    Comparison cmp;
    std::vector<report::Plot> plots;
    std::string dir;
  };
  std::vector<Pending> reports;
  const Loaded& la = loaded.front();
  const ResultFigures& a = la.figures;
  for (std::size_t i = 1; i < loaded.size(); ++i) {
    const Loaded& lb = loaded[i];
    const ResultFigures& b = lb.figures;
    Pending r;
    r.cmp = Compare(a, b);
    if (s.plots && la.result && lb.result)
      r.plots = report::OverlayPlots(a.label + " (A)", *la.result, b.label + " (B)", *lb.result);
    r.dir = s.out_dir.empty() ? (fs::path("reports") / ("compare_" + Safe(a.label) + "_vs_" + Safe(b.label))).string()
                              : s.out_dir;
    reports.push_back(std::move(r));
  }
  for (const Pending& r : reports) {
    WriteComparison(r.cmp, r.plots, r.dir, s.force, s.threads);
    if (s.quiet) continue;
    std::printf("%s (A) vs %s (B):\n", r.cmp.label_a.c_str(), r.cmp.label_b.c_str());
    for (const ComparedFigure& f : r.cmp.figures)
      if (f.contributor == "total" && f.band.empty())
        std::printf("  %-24s rms %12.6g -> %12.6g %s  (B/A %s)\n", f.output.c_str(), f.rms_a, f.rms_b,
                    f.unit.c_str(), Ratio(f).c_str());
    for (const std::string& u : r.cmp.unmatched) std::printf("  not compared: %s\n", u.c_str());
    std::printf("report: %s\n", r.dir.c_str());
  }
  return 0;
}

}  // namespace deb::tools
