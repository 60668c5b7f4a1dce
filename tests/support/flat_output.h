// An output for table and guidance tests: on the grid {1, 2} Hz, its
// contributors a, b, ... (source s_a, ..., path p) have flat PSDs equal to
// their variances (the grid is 1 Hz wide): CPS_c = v_c (f - 1).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "deb/budget/result.h"

namespace deb::test {

inline OutputResult FlatOutput(const std::vector<double>& variances, std::optional<double> rms_max,
                               const std::string& unit = "nm", const std::string& name = "position") {
  OutputResult o;
  o.name = name;
  o.signal = "x";
  o.unit = unit;
  o.rms_max = rms_max;
  o.total_psd = {0.0, 0.0};
  o.total_cps = {0.0, 0.0};
  for (std::size_t c = 0; c < variances.size(); ++c) {
    ContributorResult cr;
    cr.name = std::string(1, static_cast<char>('a' + c));
    cr.source = "s_" + cr.name;
    cr.path = "p";
    cr.psd = {variances[c], variances[c]};
    cr.cps = {0.0, variances[c]};
    cr.variance = variances[c];
    o.total_psd[0] += variances[c];
    o.total_psd[1] += variances[c];
    o.total_cps[1] += variances[c];
    o.contributors.push_back(cr);
  }
  o.variance = o.total_cps[1];
  return o;
}

}  // namespace deb::test
