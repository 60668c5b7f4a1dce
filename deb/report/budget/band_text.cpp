#include "deb/report/budget/band_text.h"

#include "deb/report/figure/plot.h"

namespace deb::report {

std::string BandText(double lo_hz, double hi_hz) { return HzText(lo_hz) + "–" + HzText(hi_hz) + " Hz"; }

}  // namespace deb::report
