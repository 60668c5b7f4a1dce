#include "deb/report/budget/report_writer.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <regex>
#include <set>
#include <sys/stat.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/results/result_writer.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/figure/gnuplot_runner.h"
#include "tests/support/cli_harness.h"

namespace deb {
namespace {

using namespace deb::test;

struct Evaluated {
  Budget budget;
  BudgetResult result;
};

Evaluated EvaluateExample() {
  Evaluated e{LoadBudgetFile(ExampleBudget()), {}};
  e.result = Evaluate(e.budget);
  return e;
}

std::uint32_t BigEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

// Relative files referenced by src="..." and href="..." (anchors and
// absolute URLs excluded).
std::set<std::string> HtmlReferences(const std::string& html) {
  std::set<std::string> refs;
  const std::regex attr(R"((?:src|href)="([^"]*)\")");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), attr); it != std::sregex_iterator(); ++it) {
    const std::string ref = (*it)[1];
    if (!ref.empty() && ref[0] != '#' && ref.rfind("data:", 0) != 0) refs.insert(ref);
  }
  return refs;
}

std::set<std::string> MarkdownReferences(const std::string& md) {
  std::set<std::string> refs;
  const std::regex link(R"(\]\(([^)\s]+)\))");
  for (auto it = std::sregex_iterator(md.begin(), md.end(), link); it != std::sregex_iterator(); ++it)
    refs.insert((*it)[1]);
  return refs;
}

}  // namespace

TEST_CASE("a report holds every plot as a valid PNG with its CSV and script, and report.pdf with the pages it "
          "reports") {
  const Evaluated e = EvaluateExample();
  const fs::path dir = TempDir("writer") / "report";
  ReportOptions options;
  options.reverse_cps = true;
  const ReportManifest m = WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, options, dir.string());

  // Overview, then per output CPS, reverse CPS, PSD and bands, then one path per contributor and output.
  const std::size_t outputs = e.result.outputs.size(), contributors = e.budget.contributors.size();
  CHECK(m.plots.size() == 1 + 4 * outputs + contributors * outputs);
  // report.pdf: a title page, the contents, then sections; its figures' SVGs are not left behind.
  CHECK(m.title_pages == 1);
  CHECK(m.pdf_pages > 3);
  CHECK(PdfPages(dir / "report.pdf") == m.pdf_pages);
  CHECK_FALSE(fs::exists(dir / "plots" / ".pdf_figures"));

  for (const auto& f : m.files) CHECK_MESSAGE(fs::is_regular_file(dir / f), f);
  for (const auto& name : m.plots) {
    CHECK(fs::file_size(dir / "plots" / (name + ".csv")) > 0);
    CHECK(fs::file_size(dir / "plots" / (name + ".gp")) > 0);
    const std::string png = ReadAll(dir / "plots" / (name + ".png"));
    REQUIRE_MESSAGE(png.size() > 24, name);
    CHECK(png.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) == 0);
    CHECK(png.compare(12, 4, "IHDR") == 0);
    CHECK(BigEndian32(png, 16) == 1200);  // width
    CHECK(BigEndian32(png, 20) == 720);   // height
  }
  for (const char* f : {"summary.json", "result.h5", "index.html", "report.md", "plots/colours.csv"})
    CHECK_MESSAGE(fs::is_regular_file(dir / f), f);
  // Each output's CSV is an export (--export csv): result.h5 holds it all.
  for (const char* f : {"z_velocity.csv", "z_displacement.csv"}) CHECK_FALSE_MESSAGE(fs::exists(dir / f), f);
  const fs::path with_csv = TempDir("writer_csv") / "report";
  const ReportManifest c = WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, options, with_csv.string(),
                                                {ExportFormat::kCsv});
  REQUIRE(outputs == 2);
  for (const OutputResult& o : e.result.outputs) {
    const std::string f = OutputCsvName(o.name);
    CHECK(std::count(c.files.begin(), c.files.end(), f) == 1);
    CHECK(ReadAll(with_csv / f) == OutputCsv(e.result, o));
  }
}

TEST_CASE("index.html and report.md reference only files that exist and nothing on the network") {
  const Evaluated e = EvaluateExample();
  const fs::path dir = TempDir("links") / "report";
  WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, {}, dir.string());
  const std::string html = ReadAll(dir / "index.html");
  // One file: no image, style sheet or script is loaded (dygraphs' licence
  // comment names its web page, which is not a reference).
  CHECK(html.find("<img") == std::string::npos);
  CHECK(html.find("<link") == std::string::npos);
  CHECK(html.find("<script src") == std::string::npos);
  const auto refs = HtmlReferences(html);
  for (const auto& r : refs) CHECK_MESSAGE(fs::is_regular_file(dir / r), r);
  CHECK(refs.count("report.pdf") == 1);
  CHECK(refs.count("summary.json") == 1);
  for (const auto& r : MarkdownReferences(ReadAll(dir / "report.md"))) CHECK_MESSAGE(fs::is_regular_file(dir / r), r);
  // Every id is unique and every in-page link has a target.
  std::set<std::string> ids;
  const std::regex id(R"re(id="([^"]*)")re");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), id); it != std::sregex_iterator(); ++it)
    CHECK_MESSAGE(ids.insert((*it)[1]).second, (*it)[1]);
  const std::regex anchor(R"re(href="#([^"]*)")re");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), anchor); it != std::sregex_iterator(); ++it)
    CHECK_MESSAGE(ids.count((*it)[1]) == 1, (*it)[1]);
}

TEST_CASE("SVG plots are XML documents and replace PNGs in index.html when PNG is not asked for") {
  const Evaluated e = EvaluateExample();
  const fs::path dir = TempDir("svg") / "report";
  ReportOptions options;
  options.formats = {PlotFormat::kSvg};
  const ReportManifest m = WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, options, dir.string());
  CHECK(m.pdf_pages == 0);
  CHECK_FALSE(fs::exists(dir / "report.pdf"));
  for (const auto& name : m.plots) {
    std::string svg = ReadAll(dir / "plots" / (name + ".svg"));
    CHECK_FALSE(fs::exists(dir / "plots" / (name + ".png")));
    CHECK((svg.rfind("<?xml", 0) == 0 || svg.rfind("<svg", 0) == 0));
    while (!svg.empty() && std::isspace(static_cast<unsigned char>(svg.back()))) svg.pop_back();
    CHECK(svg.size() > 6);
    CHECK(svg.substr(svg.size() - 6) == "</svg>");
  }
  for (const auto& r : HtmlReferences(ReadAll(dir / "index.html"))) CHECK_MESSAGE(fs::is_regular_file(dir / r), r);
}

TEST_CASE("the ASD option plots amplitude spectral densities in unit per root hertz") {
  const Evaluated e = EvaluateExample();
  const fs::path dir = TempDir("asd") / "report";
  ReportOptions options;
  options.asd = true;
  options.formats = {PlotFormat::kPng};
  WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, options, dir.string());
  CHECK(fs::is_regular_file(dir / "plots" / "z_velocity_asd.png"));
  CHECK_FALSE(fs::exists(dir / "plots" / "z_velocity_psd.png"));
  const std::string script = ReadAll(dir / "plots" / "z_velocity_asd.gp");
  CHECK(script.find("ASD [(µm/s)/√Hz]") != std::string::npos);
  // The CSV holds sqrt(PSD): compare one row with the engine.
  const std::string csv = ReadAll(dir / "plots" / "z_velocity_asd.csv");
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);  // comment
  std::getline(lines, line);  // header
  std::getline(lines, line);  // first frequency
  std::istringstream fields(line);
  std::string f, floor;
  std::getline(fields, f, ',');
  std::getline(fields, floor, ',');
  CHECK(std::stod(floor) == doctest::Approx(std::sqrt(e.result.outputs[0].contributors[0].psd[0])).epsilon(1e-8));
}

TEST_CASE("without plots the report needs no gnuplot and still writes tables, data and documents") {
  const Evaluated e = EvaluateExample();
  const fs::path dir = TempDir("noplots") / "report";
  ReportOptions options;
  options.plots = false;
  options.gnuplot = "/nonexistent/gnuplot";
  const ReportManifest m = WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, options, dir.string());
  CHECK(m.pdf_pages == 0);
  CHECK(fs::is_regular_file(dir / "index.html"));
  CHECK(fs::is_regular_file(dir / "plots" / "z_velocity_cps.csv"));
  CHECK_FALSE(fs::exists(dir / "plots" / "z_velocity_cps.png"));
  CHECK(ReadAll(dir / "index.html").find("<img") == std::string::npos);
}

TEST_CASE("invalid report options are an error before anything is drawn") {
  const Evaluated e = EvaluateExample();
  const fs::path parent = TempDir("options");
  ReportOptions options;
  options.formats = {PlotFormat::kPng, PlotFormat::kPng};
  CHECK_THROWS_WITH_AS(WriteReportDirectory(e.result, {}, options, (parent / "r").string()),
                       doctest::Contains("'png' is given twice"), InputError);
  options.formats.clear();
  CHECK_THROWS_WITH_AS(WriteReportDirectory(e.result, {}, options, (parent / "r").string()),
                       doctest::Contains("png, pdf, svg"), InputError);
  CHECK_FALSE(fs::exists(parent / "r"));
}

TEST_CASE("plots are drawn in batches, yet a failing plot is named in the error and nothing is left behind") {
  const Evaluated e = EvaluateExample();
  const fs::path parent = TempDir("batch_error");
  // The real gnuplot, except that it fails on the script that draws z_velocity_psd.png.
  const fs::path exe = WriteFile(parent / "picky-gnuplot",
                                 "#!/bin/sh\nscript=$(cat)\ncase \"$script\" in *\"set output 'z_velocity_psd.png.svg'\"*)\n"
                                 "  echo 'line 3: picky gnuplot refuses this plot' >&2; exit 1;;\nesac\n"
                                 "printf '%s\\n' \"$script\" | exec '" + report::FindGnuplot("") + "' \"$@\"\n");
  ::chmod(exe.c_str(), 0755);
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    ReportOptions options;
    options.gnuplot = exe.string();
    options.threads = threads;
    const fs::path dir = parent / ("report" + std::to_string(threads));
    CHECK_THROWS_WITH_AS(WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, options, dir.string()),
                         doctest::Contains("cannot draw plot z_velocity_psd.png: gnuplot"), WriteError);
    CHECK_THROWS_WITH_AS(WriteReportDirectory(e.result, {ExampleBudget(), 0.1}, options, dir.string()),
                         doctest::Contains("picky gnuplot refuses this plot"), WriteError);
    CHECK_FALSE(fs::exists(dir));
  }
}

}  // namespace deb

namespace deb {
using namespace deb::test;

TEST_CASE("wafer_stage's report says each thing once: its one loop drawn once, path figures listed, under 20 pages") {
  const Budget budget = LoadBudgetFile(ExampleBudget("wafer_stage.yaml"));
  const BudgetResult result = Evaluate(budget);
  const fs::path dir = TempDir("once") / "report";
  const ReportManifest m = WriteReportDirectory(result, {ExampleBudget("wafer_stage.yaml"), 0.1}, {}, dir.string());
  // One physical loop (closed as PS, T and S by three paths): Bode, |S| and |T|, Nyquist, once.
  int loop_plots = 0;
  for (const std::string& name : m.plots) loop_plots += name.rfind("loop_", 0) == 0;
  CHECK(loop_plots == 3);
  // The 15 path figures stay in plots/ (and index.html); report.pdf lists them.
  int path_plots = 0;
  for (const std::string& name : m.plots) path_plots += name.rfind("path_", 0) == 0;
  CHECK(path_plots == 15);
  CHECK(m.pdf_pages < 20);
  CHECK(PdfPages(dir / "report.pdf") == m.pdf_pages);
  fs::remove_all(dir.parent_path());
}

}  // namespace deb
