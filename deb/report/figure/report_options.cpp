#include "deb/report/figure/report_options.h"

#include <algorithm>

#include "deb/core/error.h"

namespace deb {

bool ReportOptions::Has(PlotFormat format) const {
  return std::find(formats.begin(), formats.end(), format) != formats.end();
}

bool ReportOptions::IsValid(std::string* error) const {
  if (digits < 1 || digits > 15) {
    *error = "digits must be 1..15, not " + std::to_string(digits);
    return false;
  }
  if (plots && formats.empty()) {
    *error = "no plot format given: choose one or more of " + AllowedNames<PlotFormat>();
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
