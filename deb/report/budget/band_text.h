// Internal: not part of the public API.
// Text of a frequency band for tables and captions of the budget report.
#pragma once

#include <string>

namespace deb::report {

// "0.1–1 Hz"
std::string BandText(double lo_hz, double hi_hz);

}  // namespace deb::report
