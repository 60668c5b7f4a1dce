// Internal: not part of the public API.
// An output's requirements as lines, each with its own verdict: the
// overall RMS limit first, then each band's. The report's verdicts (the box
// on report.pdf's first page, each output's section, the banner of
// index.html) give one line per requirement, green where it is met.
#pragma once

#include <string>
#include <vector>

#include "deb/budget/result.h"

namespace deb::report {

struct RequirementLine {
  std::string scope;  // kOverallScope or a band, "1–10 Hz"
  double rms = 0.0, rms_max = 0.0;
  bool pass = true;
  static constexpr const char* kOverallScope = "RMS";
  bool overall() const { return scope == kOverallScope; }  // the output's RMS limit, not a band's
};

// Empty for an output without requirements.
std::vector<RequirementLine> RequirementLines(const OutputResult& output);

// "1–10 Hz: RMS 2.1 nm against 3 nm (met)"; the overall line reads
// "RMS 2.1 nm against a limit of 3 nm (exceeded)". `unit` as displayed.
std::string RequirementSentence(const RequirementLine& line, const std::string& unit);

}  // namespace deb::report
