#include "deb/report/budget/report_documents.h"

#include <doctest/doctest.h>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/spectrum_plots.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

struct Example {
  Budget budget = LoadBudgetFile(test::ExampleBudget());
  BudgetResult result = Evaluate(budget);
  DocumentInputs Inputs(const std::string& ext) const {
    DocumentInputs in;
    in.result = &result;
    in.facts = MakeFacts(result, "b.yaml", "00ff", "today", 0.1);
    in.plots = SpectrumPlots(result, 0, {});
    in.image_extension = ext;
    in.data_files = {"summary.json"};
    return in;
  }
};

}  // namespace

TEST_CASE("index.html is one page with inline style and script, the facts, and a figure per output") {
  const Example e;
  const std::string html = IndexHtml(e.Inputs("png"));
  CHECK(html.rfind("<!DOCTYPE html>", 0) == 0);
  CHECK(html.find("<style>") != std::string::npos);
  CHECK(html.find("<link") == std::string::npos);
  CHECK(html.find("<img") == std::string::npos);
  CHECK(html.find("<script src") == std::string::npos);
  CHECK(html.find("<td>SHA-256</td><td>00ff</td>") != std::string::npos);
  for (const char* kind : {"cps", "psd", "bands"})
    CHECK(html.find("<figure class=\"chart\" data-kind=\"" + std::string(kind) + "\" data-index=\"0\">") !=
          std::string::npos);
  CHECK(html.find("data-kind=\"path\" data-index=\"" + std::to_string(e.budget.contributors.size() *
                                                                     e.result.outputs.size() - 1) + "\"") !=
        std::string::npos);
  CHECK(html.find("id=\"deb-figure-data\"") != std::string::npos);
  // dygraphs is inlined with its licence.
  CHECK(html.find("Dygraph") != std::string::npos);
  CHECK(html.find("Permission is hereby granted, free of charge") < html.find("Dygraph"));
  CHECK(html.find("<noscript>") != std::string::npos);
  // Each figure links its plot's image and data, for slides and other tools.
  CHECK(html.find("<a href=\"plots/z_velocity_cps.png\">") != std::string::npos);
  CHECK(html.find("<a href=\"plots/z_velocity_cps.csv\">") != std::string::npos);
  CHECK(html.find("id=\"" + OutputAnchor("z_velocity") + "\"") != std::string::npos);
  CHECK(html.find("report.pdf") == std::string::npos);  // not written here
}

TEST_CASE("with --asd the page's spectra open as amplitudes") {
  const Example e;
  DocumentInputs in = e.Inputs("png");
  CHECK(IndexHtml(in).find("data-kind=\"asd\"") == std::string::npos);
  in.asd = true;
  const std::string html = IndexHtml(in);
  CHECK(html.find("<figure class=\"chart\" data-kind=\"asd\" data-index=\"0\">") != std::string::npos);
  CHECK(html.find("data-kind=\"psd\"") == std::string::npos);
}

TEST_CASE("without images the documents still give every table and link the data") {
  const Example e;
  const std::string html = IndexHtml(e.Inputs(""));
  CHECK(html.find("<img") == std::string::npos);
  CHECK(html.find("plots/z_velocity_cps.csv") != std::string::npos);
  const std::string md = ReportMarkdown(e.Inputs(""));
  CHECK(md.find("![") == std::string::npos);
  CHECK(md.find("| output | unit | RMS |") != std::string::npos);
  CHECK(md.find("### Frequency bands") != std::string::npos);
  CHECK(md.find("[summary.json](summary.json)") != std::string::npos);
}

TEST_CASE("names are escaped in HTML and anchors are safe") {
  Example e;
  e.result.outline.description = "<b>a & b</b>";
  const std::string html = IndexHtml(e.Inputs("png"));
  CHECK(html.find("&lt;b&gt;a &amp; b&lt;/b&gt;") != std::string::npos);
  CHECK(OutputAnchor("z velocity/1") == "output-z_velocity_1");
}

}  // namespace deb::report
