#include "deb/report/budget/interactive_figures.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>

#include "deb/budget/engine.h"
#include "deb/budget/failure_guidance.h"
#include "deb/load/budget_yaml.h"
#include "deb/report/budget/band_plots.h"
#include "deb/report/budget/report_documents.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/plot_points.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

using nlohmann::json;

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

struct Evaluated {
  Budget budget;
  BudgetResult result;
  explicit Evaluated(const std::string& file) : budget(LoadBudgetFile(test::ExampleBudget(file))), result(Evaluate(budget)) {}
  std::string Html() const {
    DocumentInputs in;
    in.result = &result;
    in.facts = MakeFacts(result, "b.yaml", "00ff", "today", 0.1);
    return IndexHtml(in);
  }
};

}  // namespace

TEST_CASE("a figure keeps at most kMaxFigurePoints of a dense grid, with a narrow resonance's peak and both ends") {
  std::vector<double> f(40000);
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = 0.01 * std::pow(10.0, 7.0 * static_cast<double>(i) / (f.size() - 1));
  // A resonance at 37 Hz with zeta 1e-4 (half-power width 0.0074 Hz) over a 1/f^2 background.
  std::vector<double> psd(f.size()), cps(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double r = f[i] / 37.0;
    psd[i] = 1.0 / (f[i] * f[i]) + 1.0 / ((1 - r * r) * (1 - r * r) + 4e-8 * r * r);
    cps[i] = (i ? cps[i - 1] : 0.0) + psd[i];
  }
  const std::vector<std::size_t> keep = FigurePoints(f, {&psd}, {&cps});
  CHECK(keep.size() <= kMaxFigurePoints);
  CHECK(keep.size() > 100);
  CHECK(std::is_sorted(keep.begin(), keep.end()));
  CHECK(std::adjacent_find(keep.begin(), keep.end()) == keep.end());
  CHECK(keep.front() == 0);
  CHECK(keep.back() == f.size() - 1);
  const std::size_t peak = static_cast<std::size_t>(std::max_element(psd.begin(), psd.end()) - psd.begin());
  CHECK(std::binary_search(keep.begin(), keep.end(), peak));
  // A tighter limit still holds.
  CHECK(FigurePoints(f, {&psd}, {&cps}, 300).size() <= 300);
  // The same points as PlotPoints on the values themselves, pass by pass
  // (FigurePoints takes each logarithm once and thins the coordinates).
  const auto by_values = [&](std::size_t max_points) {
    std::vector<std::size_t> keep(f.size());
    for (std::size_t i = 0; i < keep.size(); ++i) keep[i] = i;
    for (double tolerance = 2e-3; tolerance == 2e-3 || (keep.size() > max_points && tolerance <= 1.0);
         tolerance *= 2.0) {
      std::vector<double> fk, pk, ck;
      for (std::size_t i : keep) {
        fk.push_back(f[i]);
        pk.push_back(psd[i]);
        ck.push_back(cps[i]);
      }
      const std::vector<std::size_t> a = PlotPoints(fk, {&pk}, fk.front(), fk.back(), PlotScale::kLog, tolerance);
      const std::vector<std::size_t> b = PlotPoints(fk, {&ck}, fk.front(), fk.back(), PlotScale::kLinear, tolerance);
      std::vector<std::size_t> both, next;
      std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(both));
      for (std::size_t k : both) next.push_back(keep[k]);
      keep = next;
    }
    return keep;
  };
  CHECK(keep == by_values(kMaxFigurePoints));
  CHECK(FigurePoints(f, {&psd}, {&cps}, 300) == by_values(300));
}

TEST_CASE("the figure data give every output's spectra by share, its bands and every path, thinned and rounded") {
  const Evaluated e("wafer_stage.yaml");
  const json data = json::parse(FigureDataJson(e.result));
  REQUIRE(data["outputs"].size() == e.result.outputs.size());
  for (std::size_t o = 0; o < e.result.outputs.size(); ++o) {
    const OutputResult& out = e.result.outputs[o];
    const json& d = data["outputs"][o];
    CAPTURE(out.name);
    CHECK(d["name"] == out.name);
    CHECK(d["pass"] == out.AllPass());
    const std::vector<double> f = d["f"];
    CHECK(f.size() <= kMaxFigurePoints);
    CHECK(std::is_sorted(f.begin(), f.end()));  // a jump is two points at one frequency
    CHECK(f.front() == doctest::Approx(e.result.grid.min_hz()));
    CHECK(f.back() == doctest::Approx(e.result.grid.max_hz()).epsilon(1e-5));
    // The CPS and PSD stack what the PNG stacks: the top-level groups ("name/") and ungrouped contributors.
    const PlotLevel level = GroupLevel(out, e.result.grid, "");
    REQUIRE(d["contributors"].size() == level.out.contributors.size());
    const std::vector<std::size_t> order = ShareOrder(level.out);
    for (std::size_t k = 0; k < order.size(); ++k) {
      CHECK(d["contributors"][k] == level.out.contributors[order[k]].name);
      CHECK(d["colours"][k] == level.styles[order[k]].colour);
    }
    CHECK(level.out.contributors.size() < out.contributors.size());  // the example groups its contributors
    // Where the cumulative RMS reaches the requirement, for the marker.
    const std::optional<double> crossing =
        CpsCrossingHz(e.result.grid.f_hz(), out.total_psd, out.total_cps, *out.rms_max * *out.rms_max);
    if (crossing) CHECK(d["crossing_hz"].get<double>() == *crossing);
    else CHECK(d["crossing_hz"].is_null());
    // The band chart's bars as the PNG's (BandBars): the groups where there are more than 8 contributors.
    const std::vector<BandBar> bars = BandBars(out, e.result.grid);
    REQUIRE(d["band_contributors"].size() == bars.size());
    for (std::size_t k = 0; k < bars.size(); ++k) CHECK(d["band_contributors"][k] == bars[k].name);
    double previous = HUGE_VAL, sum = 0.0;
    for (std::size_t k = 0; k < level.out.contributors.size(); ++k) {
      CHECK(d["psd"][k].size() == f.size());
      CHECK(d["cps"][k].size() == f.size());
      const double variance = d["cps"][k].back();
      CHECK(variance <= previous * (1 + 1e-3));  // largest first
      previous = variance;
      sum += variance;
    }
    CHECK(d["total_cps"].back().get<double>() == doctest::Approx(out.variance).epsilon(1e-3));
    CHECK(sum == doctest::Approx(out.variance).epsilon(1e-3));
    REQUIRE(d["bands"].size() == out.bands.size());
    for (std::size_t b = 0; b < out.bands.size(); ++b) {
      double band = 0.0;
      for (double v : d["band_variance"][b]) band += v;
      CHECK(band == doctest::Approx(out.bands[b].variance).epsilon(1e-3));
    }
  }
  CHECK(data["paths"].size() == e.budget.contributors.size() * e.result.outputs.size());
  for (const json& p : data["paths"]) {
    CHECK(p["f"].size() <= kMaxFigurePoints);
    for (const json& m : p["magnitude"]) CHECK(m.size() == p["f"].size());
  }
}

TEST_CASE("names cannot end the data's script element, and the page keeps exactly its own scripts") {
  Evaluated e("wafer_stage.yaml");
  e.result.outputs[0].name = "</script><script>alert(1)</script><!--";
  const std::string text = FigureDataJson(e.result);
  CHECK(text.find('<') == std::string::npos);
  CHECK(json::parse(text)["outputs"][0]["name"] == e.result.outputs[0].name);
  const std::string html = e.Html();
  CHECK(Count(html, "<script") == 3);  // dygraphs, the data, the drawing code
  CHECK(Count(html, "</script>") == 3);
  CHECK(html.find("alert(1)</script>") == std::string::npos);
}

TEST_CASE("a failing budget's page opens with a red verdict and the guidance, and FAIL cells are marked") {
  const Evaluated e("wafer_stage.yaml");
  const std::string html = e.Html();
  const std::size_t verdict = html.find("<div class=\"verdict fail\"");
  REQUIRE(verdict != std::string::npos);
  CHECK(verdict < html.find("<h2 id=\"summary\">"));
  for (const OutputResult& out : e.result.outputs) {
    const std::string fix = GuidanceText(out, e.result.grid);
    if (fix.empty()) continue;
    CHECK(html.find("<strong>FAIL</strong> " + HtmlEscape(out.name)) < html.find("<h2 id=\"summary\">"));
    CHECK(html.find(HtmlEscape(fix)) < html.find("<h2 id=\"summary\">"));
  }
  // A line per requirement, each coloured by its own verdict: position fails overall and in 0.1–10 Hz,
  // image_shift overall; the lines that pass are green, not red like the rest of a failing banner.
  const std::string banner = html.substr(verdict, html.find("</div>", verdict) - verdict);
  CHECK(Count(banner, "<p class=\"fail\"><strong>FAIL</strong> ") == 3);
  CHECK(Count(banner, "<p class=\"pass\"><strong>PASS</strong> ") >= 1);
  CHECK(banner.find("<strong>FAIL</strong> position, 0.1–10 Hz: RMS ") != std::string::npos);
  CHECK(html.find("<td class=\"fail\"><strong>FAIL</strong></td>") != std::string::npos);
  CHECK(html.find("<td><strong>FAIL</strong></td>") == std::string::npos);
  CHECK(html.find("<td>FAIL</td>") == std::string::npos);
}

TEST_CASE("a passing budget's verdict is green, one without requirements grey") {
  Evaluated e("wafer_stage.yaml");
  for (OutputResult& out : e.result.outputs) {
    out.rms_max = out.rms() * 2;
    out.band_requirements.clear();
  }
  CHECK(e.Html().find("<div class=\"verdict pass\"") != std::string::npos);
  for (OutputResult& out : e.result.outputs) out.rms_max.reset();
  const std::string html = e.Html();
  CHECK(html.find("<div class=\"verdict none\"") != std::string::npos);
  CHECK(html.find("<strong>no requirement</strong>") != std::string::npos);
  CHECK(html.find("<noscript>") != std::string::npos);
}

}  // namespace deb::report
