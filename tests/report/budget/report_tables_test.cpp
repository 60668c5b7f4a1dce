#include "deb/report/budget/report_tables.h"

#include <doctest/doctest.h>

#include <algorithm>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/figure/plot.h"

#include <cmath>
#include "tests/support/cli_harness.h"
#include "tests/support/flat_output.h"

namespace deb::report {
namespace {

using test::FlatOutput;

Table Small() {
  Table t;
  t.title = "t";
  t.header = {"name", "value", "note"};
  t.numeric = {false, true, false};
  t.rows = {{"a|b", "1.5", "x"}, {"µm", "12.25", "a very long note that goes on"}};
  t.emphasis = {{false, true, false}};
  return t;
}


}  // namespace

TEST_CASE("a failing output's contributor table gives the reduction of each RMS that meets the limit, not k") {
  // 80 + 10 + 10 against 6^2: a alone meets it at 20 + 80 / r^2 = 36, r = sqrt(5); b and c cannot.
  const Table alone = ContributorTable(FlatOutput({80.0, 10.0, 10.0}, 6.0, "um"));
  REQUIRE(alone.header[6] == "must drop");
  CHECK(alone.rows[0][6] == "2.236×");
  // b joins a in the trade-off the guidance sentence offers: 10 + 90 / r^2 = 36.
  CHECK(alone.rows[1][6] == "1.861×, each of top 2");
  CHECK(alone.rows[2][6] == "–");
  CHECK(alone.rows[1][7].empty());  // no repeated "no allocation" note
  // 49 + 25 + 16 + 10: none alone; a and b together, 26 + 74 / r^2 = 36, r = sqrt(7.4).
  const Table pair = ContributorTable(FlatOutput({49.0, 25.0, 16.0, 10.0}, 6.0, "um"));
  CHECK(pair.rows[0][6] == "2.720×, each of top 2");
  CHECK(pair.rows[1][6] == "2.720×, each of top 2");
  // One more, a, b and c: 10 + 90 / r^2 = 36; d is in neither set.
  CHECK(pair.rows[2][6] == "1.861×, each of top 3");
  CHECK(pair.rows[3][6] == "–");
  // A passing output keeps the allocation factor k on the PSD: (36 - 10) / 20.
  const Table passing = ContributorTable(FlatOutput({20.0, 10.0}, 6.0, "um"));
  CHECK(passing.header[6] == "allocation k");
  CHECK(passing.rows[0][6] == "1.300");
  const FrequencyGrid grid(std::vector<double>{1.0, 2.0});
  CHECK(GuidanceText(FlatOutput({20.0, 10.0}, 6.0, "um"), grid).empty());
  CHECK(GuidanceText(FlatOutput({80.0, 10.0, 10.0}, 6.0, "um"), grid) ==
        "position fails by 1.667×: a (80 %) must drop 2.236×, or a and b 1.861× each; the cumulative RMS reaches "
        "6 µm at 1.36 Hz.");
}

TEST_CASE("the summary table names each band requirement's largest contributor within the band") {
  BudgetResult result;
  result.grid = FrequencyGrid(std::vector<double>{1.0, 2.0});
  OutputResult o = FlatOutput({20.0, 60.0}, 10.0, "um");
  BandRequirementResult b;
  b.requirement = {1.0, 1.25, 4.0};
  b.variance = 20.0;  // a quarter of each flat PSD: 5 + 15
  o.band_requirements = {b};
  result.outputs = {o};
  const Table t = SummaryTable(result);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[1][0] == "position, 1–1.25 Hz");
  CHECK(t.rows[1][5] == "FAIL");
  CHECK(t.rows[1][6] == "b (75.0 %)");
}

TEST_CASE("text tables align columns by characters, numbers to the right, and shorten long cells") {
  const std::vector<std::string> lines = ToText(Small(), 30, 24);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == "name  value  note");
  CHECK(lines[2] == "a|b     1.5  x");
  CHECK(lines[3] == "µm    12.25  a very long…");  // the last column gets what is left of 24
}

TEST_CASE("Markdown and HTML tables escape their cells and mark emphasis") {
  const std::string md = ToMarkdown(Small());
  CHECK(md.find("| name | value | note |\n| --- | ---: | --- |\n") == 0);
  CHECK(md.find("a\\|b | **1.5** | x") != std::string::npos);
  const std::string html = ToHtml(Small());
  CHECK(html.find("<td class=\"num\"><strong>1.5</strong></td>") != std::string::npos);
  CHECK(HtmlEscape("<a & \"b\">") == "&lt;a &amp; &quot;b&quot;&gt;");
}

TEST_CASE("a long note several rows hold is said once: a mark in each row, the text below the table") {
  Table t;
  t.title = "contributors";
  t.header = {"contributor", "RMS", "note"};
  t.numeric = {false, true, false};
  const std::string shared = "no exact variance: the path has measured data";
  t.rows = {{"a", "1", shared}, {"b", "2", shared}, {"c", "3", "short"}, {"d", "4", "only this row's own long note"}};
  std::vector<std::string> notes;
  const Table merged = WithNotesBelow(t, &notes);
  CHECK(merged.rows[0][2] == "¹");
  CHECK(merged.rows[1][2] == "¹");
  CHECK(merged.rows[2][2] == "short");  // short text stays in its cell
  CHECK(merged.rows[3][2] == "²");      // the note column: below even when one row holds it
  CHECK(notes == std::vector<std::string>{"¹ " + shared, "² only this row's own long note"});
  const std::string html = ToHtml(t);
  CHECK(html.find(shared) == html.rfind(shared));  // once
  CHECK(html.find("<tfoot><tr><td class=\"notes\" colspan=\"3\">¹ " + shared + "<br>² only") != std::string::npos);
  // A long name in a text column held by one row only stays.
  Table names = t;
  names.header[2] = "source";
  notes.clear();
  CHECK(WithNotesBelow(names, &notes).rows[3][2] == "only this row's own long note");
}

TEST_CASE("the band table lists contributors by share, emphasises the largest per band and ends with the total") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const Table t = BandTable(result.outputs[0]);
  CHECK(t.header.front() == "contributor");
  CHECK(t.header.back() == "whole grid");
  REQUIRE(t.rows.size() == 3);
  CHECK(t.rows[0][0] == "floor");
  CHECK(t.rows[2][0] == "total");
  // Floor dominates the 1-10 Hz band; sensor noise the 100-1000 Hz band (the VC spectrum stops near 89 Hz).
  CHECK(t.emphasis[0][2]);
  CHECK(t.emphasis[1][4]);
  CHECK_FALSE(t.emphasis[0][4]);
}

TEST_CASE("the summary table gives status and the largest contributor of every output") {
  const Budget budget = LoadBudgetFile(test::ExampleBudget());
  const BudgetResult result = Evaluate(budget);
  const Table t = SummaryTable(result);
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0][0] == "z_velocity");
  CHECK(t.rows[0][1] == "µm/s");
  CHECK(t.rows[0][3] == "20");
  CHECK(t.rows[0][5] == "pass");
  CHECK(t.rows[0][6].rfind("floor (", 0) == 0);
  const ReportFacts f = MakeFacts(result, "b.yaml", "abc", "today", 0.5);
  CHECK(f.items[0].label == "budget");
  CHECK(f.items[0].value == "single_axis_isolator");
  CHECK(f.items.back().value == "all 2 met");
  // report.pdf's first page leaves out what it says anyway: the title, the footer's version, the verdict box.
  std::vector<std::string> elsewhere;
  for (const ReportFact& i : f.items)
    if (i.shown_elsewhere_on_pdf_title_page) elsewhere.push_back(i.label);
  CHECK(elsewhere == std::vector<std::string>{"budget", "deb version", "requirements"});
  const auto named = [](const ReportFacts& facts, const std::string& key) {
    return std::count_if(facts.items.begin(), facts.items.end(), [&](const ReportFact& i) { return i.label == key; });
  };
  CHECK(named(f, "sweep") == 0);
  // A budget with a sweep section: the report says it is the budget as written, not the sweep.
  BudgetResult swept = result;
  swept.outline.has_sweep = true;
  const ReportFacts g = MakeFacts(swept, "b.yaml", "abc", "today", 0.5);
  REQUIRE(named(g, "sweep") == 1);
  CHECK(g.items[2].value.find("not run") == 0);
  // A budget with tolerances: the report is the nominal design.
  CHECK(named(f, "tolerances") == 0);
  const BudgetResult toleranced = Evaluate(LoadBudgetFile(test::ExampleBudget("nizamoglu2015_tolerances.yaml")));
  CHECK(toleranced.outline.uncertain_parameters == 4);
  const ReportFacts nominal = MakeFacts(toleranced, "t.yaml", "abc", "today", 0.5);
  REQUIRE(named(nominal, "tolerances") == 1);
  CHECK(nominal.items[2].value == "not sampled: this report is the nominal design (deb uncertainty samples the 4 "
                             "uncertain parameters)");
  // The conventions explain the contributor tables' last column as it is: k where outputs pass, "must drop"
  // where one fails (wafer_stage's position).
  const auto explains = [](const ReportFacts& facts, const std::string& start) {
    return std::any_of(facts.conventions.begin(), facts.conventions.end(),
                       [&](const std::string& c) { return c.rfind(start, 0) == 0; });
  };
  CHECK(explains(f, "Allocation k"));
  CHECK_FALSE(explains(f, "Must drop"));
  const BudgetResult failing = Evaluate(LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml")));
  REQUIRE_FALSE(failing.outputs[0].pass());
  CHECK(explains(MakeFacts(failing, "w.yaml", "abc", "today", 0.5), "Must drop"));
}

TEST_CASE("the group table lists every group depth first, indented, with its members and the sums") {
  const BudgetResult r = Evaluate(LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml")));
  const OutputResult& o = r.outputs[0];
  const Table t = GroupTable(o, 4);
  REQUIRE(t.rows.size() == 5);
  CHECK(t.rows[0][0] == "environment");
  CHECK(t.rows[2][0] == "stage");
  CHECK(t.rows[3][0] == "  drive");  // stage/drive, one level down
  CHECK(t.rows[2][1] == "cable_slab, y_crosstalk, drive/");
  double environment = 0.0;
  for (const ContributorResult& c : o.contributors)
    if (c.group == "environment") environment += c.variance;
  CHECK(t.rows[0][2] == Sig(std::sqrt(environment), 4));
  CHECK(t.header.size() == 4 + o.bands.size());
  // No groups, no rows.
  CHECK(GroupTable(Evaluate(LoadBudgetFile(test::ExampleBudget())).outputs[0]).rows.empty());
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("the covariance table: one row per pair, correlations from the matrices, the largest part per pair") {
  CovarianceResult cov;
  cov.outputs = {"x", "y", "rz"};
  cov.units = {"nm", "nm", "nrad"};
  const auto matrix = [](double xy, double xr, double yr, double d) {
    Eigen::MatrixXd m(3, 3);
    m << d, xy, xr, xy, d, yr, xr, yr, d;
    return m;
  };
  cov.contributors = {{"floor", matrix(1.0, -2.0, 0.0, 4.0)}, {"stage", matrix(3.0, 1.0, 0.0, 4.0)}};
  cov.matrix = cov.contributors[0].matrix + cov.contributors[1].matrix;  // variances 8, covariances 4, -1, 0
  Table t = CovarianceTable(cov, 4);
  REQUIRE(t.rows.size() == 3);
  CHECK(t.header.size() == 5);  // no exact matrix: no exact column
  CHECK(t.rows[0] == std::vector<std::string>{"x", "y", "0.500", "4.000 nm²", "stage (75.0 %)"});
  CHECK(t.rows[1] == std::vector<std::string>{"x", "rz", "-0.125", "-1.000 nm·nrad", "floor (200 %)"});
  CHECK(t.rows[2] == std::vector<std::string>{"y", "rz", "0", "0 nm·nrad", "–"});  // no contributor correlates them
  // floor's 200 % is explained below the table.
  REQUIRE(t.notes.size() == 1);
  CHECK(t.notes[0].find("above 100 %") != std::string::npos);
  cov.exact_matrix = 2.0 * cov.matrix;
  t = CovarianceTable(cov, 4);
  CHECK(t.header[4] == "exact correlation");
  CHECK(t.rows[0][4] == "0.500");
  // The rounding of an uncorrelated pair (correlation 1e-18, nizamoglu2015's
  // x and alpha velocities): "≈ 0", no contributor, and a note.
  cov.exact_matrix.reset();
  cov.contributors[0].matrix(1, 2) = cov.contributors[0].matrix(2, 1) = 8e-18;
  cov.contributors[1].matrix(1, 2) = cov.contributors[1].matrix(2, 1) = -3e-18;
  cov.matrix = cov.contributors[0].matrix + cov.contributors[1].matrix;
  t = CovarianceTable(cov, 4);
  CHECK(t.rows[2] == std::vector<std::string>{"y", "rz", "≈ 0", "≈ 0 nm·nrad", "–"});
  REQUIRE(t.notes.size() == 2);
  CHECK(t.notes[0].find("≈ 0: a correlation below 1e-09") == 0);
  // Above the bound it is data.
  cov.matrix(1, 2) = cov.matrix(2, 1) = 8e-8;
  CHECK(CovarianceTable(cov, 4).rows[2][2] == "1.00e-08");
  const std::string md = ToMarkdown(t), html = ToHtml(t);
  CHECK(md.find("\n\n≈ 0: a correlation") != std::string::npos);
  CHECK(html.find("<tfoot>") != std::string::npos);
  CHECK(html.find("partly cancel") != std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("the channel table lists each contributor's channels largest first, a rounding zero as 0, the cross terms") {
  OutputResult o = FlatOutput({13.0, 5.0}, 10.0, "um");
  ContributorResult& a = o.contributors[0];
  a.channels = {{"x", {}, {}, 4.0}, {"z", {}, {}, 9.0}, {"y", {}, {}, 1e-30}};
  a.cross_variance = 0.0;
  ContributorResult& b = o.contributors[1];  // correlated channels: 3 + 3 + cross terms -1 = 5
  b.channels = {{"u", {}, {}, 3.0}, {"v", {}, {}, 3.0}};
  b.cross_variance = -1.0;
  const Table t = ChannelTable(o, 4);
  REQUIRE(t.rows.size() == 6);
  CHECK(t.header == std::vector<std::string>{"contributor", "channel", "RMS", "share", "of contributor"});
  CHECK(t.rows[0] == std::vector<std::string>{"a", "z", "3.000", "50.0 %", "69.2 %"});
  CHECK(t.rows[1] == std::vector<std::string>{"a", "x", "2.000", "22.2 %", "30.8 %"});
  CHECK(t.rows[2] == std::vector<std::string>{"a", "y", "0", "0 %", "0 %"});  // 1e-30 of 13: rounding
  CHECK(t.rows[3][1] == "u");
  CHECK(t.rows[4][1] == "v");
  CHECK(t.rows[5][1] == "cross terms (variance)");
  CHECK(t.rows[5][2] == "-1.000 µm²");
  CHECK(t.rows[5][3] == "-5.56 %");
  CHECK(t.rows[5][4] == "-20.0 %");
  // No breakdown, no rows.
  CHECK(ChannelTable(FlatOutput({1.0}, 2.0, "um"), 4).rows.empty());
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a contributor of tones alone gets no 'grid holds' note: its variance is exact on any grid") {
  // optical_table's ripple: a 5 mN tone at 50 Hz; the other contributors are densities.
  const BudgetResult r = Evaluate(LoadBudgetFile(test::ExampleBudget("optical_table.yaml")));
  const OutputResult& gap = r.outputs.at(0);
  const Table t = ContributorTable(gap, 4);
  const std::size_t note = t.header.size() - 1;
  REQUIRE(t.header[note] == "note");
  bool ripple = false;
  for (const auto& row : t.rows)
    if (row[0] == "ripple") {
      ripple = true;
      CHECK(row[note].empty());  // it has an exact variance (the tone itself): no note at all
    }
  CHECK(ripple);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a contributor the model leaves uncoupled, computed as rounding, reads 0 in the contributor and band tables") {
  // nizamoglu2015_h0: the floor reaches beta_velocity only through rounding
  // (RMS 6.1e-13 of 22 µrad/s); a part at most 1e-24 of the whole is 0.
  OutputResult o = test::FlatOutput({4.0, 3e-25, 1e-20}, std::nullopt, "um");
  BandResult band;
  band.band = {1.0, 2.0};
  band.variance = o.variance;
  band.contributor_variance = {4.0, 3e-25, 1e-20};
  o.bands = {band};
  const Table t = ContributorTable(o, 4);
  const auto row_of = [&](const Table& table, const std::string& name) {
    for (const auto& row : table.rows)
      if (row[0] == name) return row;
    FAIL("no row " << name);
    return std::vector<std::string>{};
  };
  CHECK(row_of(t, "b")[3] == "0");
  CHECK(row_of(t, "b")[4] == "0 %");
  CHECK(row_of(t, "c")[3] == "1.000e-10");  // above the bound: data
  const Table bands = BandTable(o, 4);
  CHECK(row_of(bands, "b")[1] == "0");
  CHECK(row_of(bands, "b")[2] == "0");
  CHECK(row_of(bands, "c")[1] == "1.000e-10");
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a mode the output does not see, computed as rounding, has a share of 0 %; a small real share stays") {
  // nastran_beam listed 8.73e-34 % beside shares of order 10 %.
  OutputResult o = test::FlatOutput({4.0}, std::nullopt, "um");
  o.contributors[0].top_modes = {{1, 12.0, 0.02, 3.6, 0.9}, {2, 40.0, 0.02, 3.5e-36, 8.73e-36}, {3, 80.0, 0.02, -7e-6, -1.76e-6}};
  const Table t = ModeTable(o);
  REQUIRE(t.rows.size() == 4);
  CHECK(t.rows[0][4] == "90.0 %");
  CHECK(t.rows[1][4] == "0 %");
  // A mode that cancels others a little: data, not rounding, but not in
  // e-notation either (metrology_frame read "-1.76e-04 %").
  CHECK(t.rows[2][4] == "< 0.01 %");
  // The modes not listed hold the rest: 1 - 0.9 + 1.76e-6, so that the shares add up to 100 %.
  CHECK(t.rows[3][1] == "the others");
  CHECK(t.rows[3][4] == "10.0 %");
  // Listed modes that hold it all get no such row.
  o.contributors[0].top_modes = {{1, 12.0, 0.02, 3.0, 0.75}, {2, 40.0, 0.02, 1.0, 0.25}};
  CHECK(ModeTable(o).rows.size() == 2);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("the measurement table's rows add up: the covered range outside the listed bands gets a row of its own") {
  // Bands 0.1-1, 1-10, 10-100 Hz; measured over 0.2-50 Hz: only 1-10 Hz is
  // covered whole; the rest, 0.2-1 and 10-50 Hz, is the covered row less it.
  OutputResult o = test::FlatOutput({4.0}, std::nullopt, "nm");
  o.bands.resize(3);
  const double edges[] = {0.1, 1.0, 10.0, 100.0};
  for (std::size_t b = 0; b < 3; ++b) {
    o.bands[b].band = {edges[b], edges[b + 1]};
    o.bands[b].variance = 1.0;
  }
  ReferenceResult m;
  m.name = "measured";
  m.covered_lo_hz = 0.2;
  m.covered_hi_hz = 50.0;
  m.variance = 9.0;
  m.budget_variance = 2.5;
  m.band_variance = {std::nullopt, 4.0, std::nullopt};
  o.references = {m};
  const Table t = ReferenceTable(o, 4);
  REQUIRE(t.rows.size() == 3);
  CHECK(t.rows[0][1] == "1–10 Hz");
  CHECK(t.rows[1][1] == "rest: 0.2–1 Hz, 10–50 Hz");
  CHECK(t.rows[1][2] == Sig(std::sqrt(1.5), 4));  // 2.5 - 1
  CHECK(t.rows[1][3] == Sig(std::sqrt(5.0), 4));  // 9 - 4
  CHECK(t.rows[2][1] == "covered 0.2–50 Hz");
  // Covered bands that are the whole covered range leave no rest.
  o.references[0].covered_lo_hz = 1.0;
  o.references[0].covered_hi_hz = 10.0;
  o.references[0].variance = 4.0;
  o.references[0].budget_variance = 1.0;
  CHECK(ReferenceTable(o, 4).rows.size() == 2);
}

TEST_CASE("a measurement the budget does not explain is said on the first page, with how much it explains") {
  const BudgetResult r = Evaluate(LoadBudgetFile(test::ExampleBudget("wafer_stage.yaml")));
  const ReferenceResult& m = r.outputs[0].references.at(0);  // position: measured 1.51x the budget
  const double ratio = std::sqrt(m.variance / m.budget_variance);
  REQUIRE(ratio > kReferenceMismatch);
  const std::vector<std::string> w = MeasurementWarnings(r);
  REQUIRE(w.size() == 1);
  CHECK(w[0].find(Sig(ratio, 3) + "× the budget's RMS") != std::string::npos);
  CHECK(w[0].find("explains " + Share(m.budget_variance, m.variance)) != std::string::npos);
  CHECK(w[0].find(Sig(std::sqrt(m.variance - m.budget_variance), 4) + " nm RMS unexplained") != std::string::npos);
  // Within the factor either way: nothing to say; a pessimistic budget is said as such.
  BudgetResult agree = r;
  agree.outputs[0].references[0].variance = 1.3 * m.budget_variance;
  CHECK(MeasurementWarnings(agree).empty());
  agree.outputs[0].references[0].variance = 0.5 * m.budget_variance;
  REQUIRE(MeasurementWarnings(agree).size() == 1);
  CHECK(MeasurementWarnings(agree)[0].find("pessimistic") != std::string::npos);
  CHECK(MeasurementWarnings(Evaluate(LoadBudgetFile(test::ExampleBudget()))).empty());
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("the parameters table prints units as the figures do and says what a unit '–' means") {
  BudgetOutline outline;
  outline.parameters = {{"t_io", "100 us", "delay", false, 100.0, "us"}, {"v", "6.25 um/s", "", false, 6.25, "um/s"}};
  const Table units = ParametersTable(outline, 4);
  CHECK(units.title == "Parameters");
  CHECK(units.rows[0][2] == "µs");
  CHECK(units.rows[1][2] == "µm/s");
  outline.parameters.push_back({"Kv", "50", "skyhook gain, N/(mm/s)", false, 50.0, ""});
  const Table plain = ParametersTable(outline, 4);
  CHECK(plain.rows[2][2] == "–");
  CHECK(plain.title == "Parameters; unit –: a plain number, in the units of the field that uses it");
}

}  // namespace deb::report
