#include "deb/report/budget/band_text.h"

#include "deb/report/figure/plot.h"

namespace deb::report {

std::string BandText(double lo_hz, double hi_hz) { return Short(lo_hz) + "–" + Short(hi_hz) + " Hz"; }

}  // namespace deb::report
