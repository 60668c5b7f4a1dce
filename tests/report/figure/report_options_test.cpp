#include "deb/report/figure/report_options.h"

#include <doctest/doctest.h>

#include "deb/core/error.h"

namespace deb {

TEST_CASE("plot formats parse from their names and an unknown one lists the allowed values") {
  CHECK(ParsePlotFormat("png") == PlotFormat::kPng);
  CHECK(ParsePlotFormat("pdf") == PlotFormat::kPdf);
  CHECK(ParsePlotFormat("svg") == PlotFormat::kSvg);
  for (PlotFormat f : {PlotFormat::kPng, PlotFormat::kPdf, PlotFormat::kSvg}) CHECK(ParsePlotFormat(ToString(f)) == f);
  CHECK_THROWS_WITH_AS(ParsePlotFormat("gif"), "unknown plot format 'gif'; allowed: png, pdf, svg", InputError);
}

TEST_CASE("report options are valid by default and reject empty or repeated formats") {
  std::string why;
  ReportOptions o;
  CHECK(o.IsValid(&why));
  CHECK(o.Has(PlotFormat::kPng));
  CHECK(o.Has(PlotFormat::kPdf));
  CHECK_FALSE(o.Has(PlotFormat::kSvg));
  o.formats = {PlotFormat::kSvg, PlotFormat::kSvg};
  CHECK_FALSE(o.IsValid(&why));
  CHECK(why == "plot format 'svg' is given twice");
  o.formats.clear();
  CHECK_FALSE(o.IsValid(&why));
  o.plots = false;
  CHECK(o.IsValid(&why));  // no plots, no formats needed
}

}  // namespace deb
