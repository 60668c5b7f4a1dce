#include "deb/report/report_options.h"

#include <algorithm>

#include "deb/core/error.h"

namespace deb {

std::string ToString(PlotFormat format) {
  switch (format) {
    case PlotFormat::kPng: return "png";
    case PlotFormat::kPdf: return "pdf";
    case PlotFormat::kSvg: return "svg";
  }
  return "?";
}

PlotFormat ParsePlotFormat(const std::string& text) {
  for (PlotFormat f : {PlotFormat::kPng, PlotFormat::kPdf, PlotFormat::kSvg})
    if (text == ToString(f)) return f;
  throw InputError("unknown plot format '" + text + "': allowed are png, pdf, svg");
}

bool ReportOptions::Has(PlotFormat format) const {
  return std::find(formats.begin(), formats.end(), format) != formats.end();
}

bool ReportOptions::IsValid(std::string* error) const {
  if (plots && formats.empty()) {
    *error = "no plot format given: choose one or more of png, pdf, svg";
    return false;
  }
  for (std::size_t i = 0; i < formats.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (formats[i] == formats[j]) {
        *error = "plot format '" + ToString(formats[i]) + "' is given twice";
        return false;
      }
  return true;
}

}  // namespace deb
