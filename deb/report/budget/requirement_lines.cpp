#include "deb/report/budget/requirement_lines.h"

#include "deb/report/budget/band_text.h"
#include "deb/report/figure/plot.h"

namespace deb::report {

std::vector<RequirementLine> RequirementLines(const OutputResult& o) {
  std::vector<RequirementLine> lines;
  if (o.rms_max) lines.push_back({RequirementLine::kOverallScope, o.rms(), *o.rms_max, o.pass()});
  for (const BandRequirementResult& b : o.band_requirements)
    lines.push_back({BandText(b.requirement.lo_hz, b.requirement.hi_hz), b.rms(), b.requirement.rms_max, b.pass()});
  return lines;
}

std::string RequirementSentence(const RequirementLine& line, const std::string& unit) {
  const std::string verdict = line.pass ? " (met)" : " (exceeded)";
  if (line.overall())
    return "RMS " + Sig(line.rms, 4) + " " + unit + " against a limit of " + Short(line.rms_max) + " " + unit + verdict;
  return line.scope + ": RMS " + Sig(line.rms, 4) + " " + unit + " against " + Short(line.rms_max) + " " + unit +
         verdict;
}

}  // namespace deb::report
