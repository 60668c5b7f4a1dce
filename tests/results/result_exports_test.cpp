// result.mat and result.xlsx (deb/results/result_mat.h, result_xlsx.h) of a small
// hand-made BudgetResult: the .mat is read back with deb's own MatFile (struct
// fields by "a.b.c"), every value exactly (the file stores the doubles); the
// .xlsx, a zip of XML, is read back with unzip: sheet names, header cells and
// numbers, equal to the result's to a relative 1e-15 (libxlsxwriter writes
// 16 significant digits).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/core/error.h"
#include "deb/formats/mat_file.h"
#include "deb/results/result_exports.h"
#include "deb/results/result_mat.h"
#include "deb/results/result_xlsx.h"
#include "deb/formats/xlsx_file.h"
#include "tests/support/cli_harness.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using test::Contains;

// Grid 1, 2, 4 Hz; contributor a: PSD 1, b: PSD 2 (trapezoid CPS 0, 1, 3 and
// 0, 2, 6); the output's variance 9 (RMS 3) against rms_max 2: FAIL.
BudgetResult SmallResult() {
  BudgetResult r;
  r.outline.name = "small";
  r.grid = FrequencyGrid({1.0, 2.0, 4.0});
  OutputResult o;
  o.name = "x pos";
  o.unit = "nm";
  ContributorResult a, b;
  a.name = "a";
  a.group = "stage/amp";
  a.source = "sa";
  a.path = "pa";
  a.psd = {1, 1, 1};
  a.cps = {0, 1, 3};
  a.variance = 3;
  a.exact_variance = 3.25;
  a.tones = {{3.0, 0.5}};
  b.name = "b";
  b.psd = {2, 2, 2};
  b.cps = {0, 2, 6};
  b.variance = 6;
  o.contributors = {a, b};
  o.total_psd = {3, 3, 3};
  o.total_cps = {0, 3, 9};
  o.variance = 9;
  o.rms_max = 2.0;
  o.bands = {{{1, 2}, 3, {1, 2}}, {{2, 4}, 6, {2, 4}}};
  BandRequirementResult req;
  req.requirement = {2, 4, 3.0};
  req.variance = 6;
  o.band_requirements = {req};
  r.outputs.push_back(o);
  OutputResult second = o;  // a name MATLAB and Excel must change
  second.name = "Summary[2]:*?";
  second.rms_max.reset();
  second.band_requirements.clear();
  r.outputs.push_back(second);
  return r;
}

Eigen::MatrixXd Mat(std::initializer_list<std::initializer_list<double>> rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(rows.begin()->size()));
  Eigen::Index i = 0;
  for (const auto& row : rows) {
    Eigen::Index j = 0;
    for (double v : row) m(i, j++) = v;
    ++i;
  }
  return m;
}

TEST_CASE("MatlabName: valid identifiers of at most 63 characters, unique") {
  std::vector<std::string> taken;
  CHECK(MatlabName("x pos", taken) == "x_pos");
  CHECK(MatlabName("x-pos", taken) == "x_pos_2");
  CHECK(MatlabName("2nd", taken) == "x2nd");
  CHECK(MatlabName("_a", taken) == "x_a");
  CHECK(MatlabName("", taken) == "x");
  CHECK(MatlabName("Ü", taken) == "x__");  // two UTF-8 bytes
  const std::string long_name(70, 'a');
  CHECK(MatlabName(long_name, taken) == std::string(63, 'a'));
  CHECK(MatlabName(long_name, taken) == std::string(61, 'a') + "_2");
}

TEST_CASE("XlsxSheetName: Excel's 31 characters, no []:*?/\\, unique ignoring case") {
  std::vector<std::string> taken;
  CHECK(formats::XlsxSheetName("Summary", "", taken) == "Summary");
  CHECK(formats::XlsxSheetName("summary", "", taken) == "summary~2");
  CHECK(formats::XlsxSheetName("a[b]:c*d?e/f\\g", "", taken) == "a_b__c_d_e_f_g");
  CHECK(formats::XlsxSheetName("'quoted'", "", taken) == "_quoted_");
  const std::string long_name(40, 'x');
  const std::string traces = formats::XlsxSheetName(long_name, " traces", taken);
  CHECK(traces == std::string(24, 'x') + " traces");
  CHECK(formats::XlsxSheetName(long_name, " traces", taken) == std::string(22, 'x') + "~2 traces");
  // Shortened at a character, not inside one: 30 x and a two-byte é fit 31 characters.
  const std::string accented = std::string(30, 'y') + "\xC3\xA9" + "zz";
  CHECK(formats::XlsxSheetName(accented, "", taken) == std::string(30, 'y') + "\xC3\xA9");
}

TEST_CASE("result.mat read back with MatFile: the grid, each output's struct, exact values") {
  const fs::path dir = test::TempDir("result_mat");
  const std::string file = (dir / "result.mat").string();
  const BudgetResult r = SmallResult();
  WriteResultMat(r, file);
  formats::MatFile m(file);
  CHECK(m.variables() ==
        std::vector<std::string>{"f_hz", "budget_name", "deb_version", "output_names", "output_fields", "outputs",
                                 "warnings"});
  CHECK(m.Matrix("f_hz") == Mat({{1}, {2}, {4}}));  // a column
  CHECK(m.Names("output_names") == std::vector<std::string>{"x pos", "Summary[2]:*?"});
  CHECK(m.Names("output_fields") == std::vector<std::string>{"x_pos", "Summary_2____"});
  CHECK(m.Names("outputs.x_pos.name") == std::vector<std::string>{"x pos"});  // a char row: one name
  CHECK(m.Names("outputs.Summary_2____.name") == std::vector<std::string>{"Summary[2]:*?"});
  CHECK(m.Names("outputs.x_pos.unit") == std::vector<std::string>{"nm"});
  CHECK(m.Names("outputs.x_pos.contributors") == std::vector<std::string>{"a", "b"});
  CHECK(m.Matrix("outputs.x_pos.psd") == Mat({{1, 2}, {1, 2}, {1, 2}}));
  CHECK(m.Matrix("outputs.x_pos.cps") == Mat({{0, 0}, {1, 2}, {3, 6}}));
  CHECK(m.Matrix("outputs.x_pos.total_psd") == Mat({{3}, {3}, {3}}));
  CHECK(m.Matrix("outputs.x_pos.total_cps") == Mat({{0}, {3}, {9}}));
  CHECK(m.Matrix("outputs.x_pos.variance") == Mat({{9}}));
  CHECK(m.Matrix("outputs.x_pos.rms") == Mat({{3}}));
  CHECK(m.Matrix("outputs.x_pos.rms_max") == Mat({{2}}));
  CHECK(m.Matrix("outputs.x_pos.pass") == Mat({{0}}));
  CHECK(m.Matrix("outputs.x_pos.contributor_variance") == Mat({{3}, {6}}));
  CHECK(m.Matrix("outputs.x_pos.contributor_rms") == Mat({{std::sqrt(3.0)}, {std::sqrt(6.0)}}));
  CHECK(m.Matrix("outputs.x_pos.share") == Mat({{3.0 / 9.0}, {6.0 / 9.0}}));
  CHECK(m.Matrix("outputs.x_pos.tones.f_hz") == Mat({{3}}));
  CHECK(m.Matrix("outputs.x_pos.tones.variance") == Mat({{0.5}}));
  CHECK(m.Names("outputs.x_pos.tones.contributor") == std::vector<std::string>{"a"});
  CHECK(m.Matrix("outputs.x_pos.bands.lo_hz") == Mat({{1}, {2}}));
  CHECK(m.Matrix("outputs.x_pos.bands.hi_hz") == Mat({{2}, {4}}));
  CHECK(m.Matrix("outputs.x_pos.bands.variance") == Mat({{3}, {6}}));
  CHECK(m.Matrix("outputs.x_pos.bands.contributor_variance") == Mat({{1, 2}, {2, 4}}));
  CHECK(m.Matrix("outputs.x_pos.band_requirements.rms") == Mat({{std::sqrt(6.0)}}));
  CHECK(m.Matrix("outputs.x_pos.band_requirements.pass") == Mat({{1}}));
  CHECK(m.Names("outputs.x_pos.groups.name") == std::vector<std::string>{"stage", "stage/amp"});
  CHECK(m.Matrix("outputs.x_pos.groups.variance") == Mat({{3}, {3}}));
  CHECK(m.Matrix("outputs.x_pos.groups.share") == Mat({{3.0 / 9.0}, {3.0 / 9.0}}));
  CHECK(m.Matrix("outputs.x_pos.references.psd").rows() == 3);
  CHECK(m.Matrix("outputs.x_pos.references.psd").cols() == 0);
  // No exact variance for b, and no requirement on the second output: NaN,
  // which MatFile refuses as an input, naming where it is.
  CHECK_THROWS_WITH_AS(m.Matrix("outputs.x_pos.exact_variance"), doctest::Contains("exact_variance(2,1) = nan"),
                       InputError);
  CHECK_THROWS_WITH_AS(m.Matrix("outputs.Summary_2____.rms_max"), doctest::Contains("rms_max(1,1) = nan"),
                       InputError);
  CHECK_THROWS_WITH_AS(m.Matrix("outputs.x_pos.nothing"),
                       doctest::Contains("the struct 'outputs.x_pos' has no field 'nothing' (its fields: name, signal"),
                       InputError);
  CHECK_THROWS_WITH_AS(m.Matrix("f_hz.x"), doctest::Contains("not a 1x1 struct"), InputError);
}

// The text of `member` of the zip `file`, by unzip.
std::string Unzipped(const fs::path& file, const std::string& member) {
  const test::Command c = test::Shell("unzip -p '" + file.string() + "' '" + member + "'");
  REQUIRE_MESSAGE(c.exit_code == 0, "unzip -p " << member << ": " << c.err);
  return c.out;
}

// A sheet's cells by reference ("B2"): the number (<v>) or inline text (<t>).
std::map<std::string, std::string> Cells(const std::string& xml) {
  std::map<std::string, std::string> cells;
  static const std::regex cell("<c r=\"([A-Z]+[0-9]+)\"[^>]*>(?:<v>([^<]*)</v>|<is><t[^>]*>([^<]*)</t></is>)</c>");
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), cell); it != std::sregex_iterator(); ++it)
    cells[(*it)[1]] = (*it)[2].matched ? (*it)[2].str() : (*it)[3].str();
  return cells;
}

void CheckNumber(const std::map<std::string, std::string>& cells, const std::string& ref, double expected) {
  INFO(ref);
  REQUIRE(cells.count(ref) == 1);
  const double v = std::strtod(cells.at(ref).c_str(), nullptr);
  CHECK(std::abs(v - expected) <= 1e-15 * std::abs(expected));
}

TEST_CASE("result.xlsx read back with unzip: sheets, headers with units, numbers as numbers") {
  const fs::path dir = test::TempDir("result_xlsx");
  const fs::path file = dir / "result.xlsx";
  WriteResultXlsx(SmallResult(), file.string());
  const std::string workbook = Unzipped(file, "xl/workbook.xml");
  std::vector<std::string> sheets;
  static const std::regex sheet("<sheet name=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(workbook.begin(), workbook.end(), sheet); it != std::sregex_iterator(); ++it)
    sheets.push_back((*it)[1]);
  CHECK(sheets == std::vector<std::string>{"Summary", "x pos", "x pos bands", "x pos traces", "Summary_2____",
                                           "Summary_2____ bands", "Summary_2____ traces"});

  const auto summary = Cells(Unzipped(file, "xl/worksheets/sheet1.xml"));
  CHECK(summary.at("A1") == "Output");
  CHECK(summary.at("C1") == "RMS [output unit]");
  CHECK(summary.at("A2") == "x pos");
  CheckNumber(summary, "C2", 3.0);
  CheckNumber(summary, "D2", 2.0);
  CHECK(summary.at("E2") == "FAIL");
  CHECK(summary.at("G2") == "b");
  CheckNumber(summary, "H2", 100.0 * 6.0 / 9.0);
  CHECK(summary.at("E3") == "no requirement");
  CHECK(summary.count("D3") == 0);  // no rms_max: an empty cell
  const std::string summary_xml = Unzipped(file, "xl/worksheets/sheet1.xml");
  CHECK(Contains(summary_xml, "<pane ySplit=\"1\""));  // the header row stays in view
  CHECK(Contains(summary_xml, "<col min=\"1\" max=\"1\" width=\""));
  // FAIL in red: its cell's style has a font of colour FFFF0000.
  CHECK(Contains(Unzipped(file, "xl/styles.xml"), "<color rgb=\"FFFF0000\"/>"));

  const auto contributors = Cells(Unzipped(file, "xl/worksheets/sheet2.xml"));
  CHECK(contributors.at("E1") == "RMS [nm]");
  CHECK(contributors.at("G1") == "Variance [nm^2]");
  CHECK(contributors.at("A2") == "b");  // largest first
  CheckNumber(contributors, "E2", std::sqrt(6.0));
  CheckNumber(contributors, "F2", 100.0 * 6.0 / 9.0);
  CHECK(contributors.count("H2") == 0);  // b has no exact variance
  CHECK(contributors.at("A3") == "a");
  CHECK(contributors.at("B3") == "stage/amp");
  CheckNumber(contributors, "H3", 3.25);
  // Allocation k = (rms_max^2 - (variance - own)) / own: b (4 - 3) / 6; a (4 - 6) / 3 < 0, none.
  CheckNumber(contributors, "J2", 1.0 / 6.0);
  CHECK(contributors.count("J3") == 0);
  CHECK(contributors.at("A4") == "total");
  CheckNumber(contributors, "E4", 3.0);

  const auto bands = Cells(Unzipped(file, "xl/worksheets/sheet3.xml"));
  CHECK(bands.at("C1") == "Total RMS [nm]");
  CHECK(bands.at("D1") == "a RMS [nm]");
  CheckNumber(bands, "A3", 2.0);
  CheckNumber(bands, "C3", std::sqrt(6.0));
  CheckNumber(bands, "E3", 2.0);  // b in 2-4 Hz: sqrt(4)
  CHECK(bands.at("E5") == "Verdict");  // the band requirements, after a blank row
  CHECK(bands.at("E6") == "PASS");

  const auto traces = Cells(Unzipped(file, "xl/worksheets/sheet4.xml"));
  CHECK(traces.at("A1") == "f [Hz]");
  CHECK(traces.at("B1") == "Total PSD [nm^2/Hz]");
  CHECK(traces.at("C1") == "PSD a [nm^2/Hz]");
  CHECK(traces.at("E1") == "Total CPS [nm^2]");
  CHECK(traces.at("G1") == "CPS b [nm^2]");
  CheckNumber(traces, "A4", 4.0);
  CheckNumber(traces, "D4", 2.0);
  CheckNumber(traces, "E4", 9.0);
  CheckNumber(traces, "G4", 6.0);
  // Numbers are stored as numbers: no text type on a number cell.
  CHECK(Contains(Unzipped(file, "xl/worksheets/sheet4.xml"), "<c r=\"G4\"><v>6</v></c>"));
}

TEST_CASE("WriteResultExports: result.mat and result.xlsx once each, in the order asked") {
  const fs::path dir = test::TempDir("exports");
  const auto written =
      WriteResultExports(SmallResult(), {ExportFormat::kXlsx, ExportFormat::kMat, ExportFormat::kXlsx}, dir.string());
  CHECK(written == std::vector<std::string>{"result.xlsx", "result.mat"});
  CHECK(fs::is_regular_file(dir / "result.xlsx"));
  CHECK(fs::is_regular_file(dir / "result.mat"));
  CHECK_THROWS_WITH_AS(ParseExportFormat("pdf"), doctest::Contains("unknown export format 'pdf'; allowed: csv, mat, xlsx"),
                       InputError);
}

TEST_CASE("an export that cannot be written is a WriteError naming the file, and leaves nothing") {
  const fs::path dir = test::TempDir("exports_fail");
  const fs::path missing = dir / "no_such_dir";
  CHECK_THROWS_WITH_AS(WriteResultMat(SmallResult(), (missing / "r.mat").string()),
                       doctest::Contains((missing / "r.mat").string().c_str()), WriteError);
  CHECK_THROWS_WITH_AS(WriteResultXlsx(SmallResult(), (missing / "r.xlsx").string()),
                       doctest::Contains((missing / "r.xlsx").string().c_str()), WriteError);
  CHECK_FALSE(fs::exists(missing));
}

}  // namespace
}  // namespace deb
