#include "deb/spectra/third_octave.h"

#include <cmath>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

// f = f_ref * base^(exponent_step * k): base 2 with step 1/3, or base 10 with
// step 1/10 (10^(k/10) = (10^(3/10))^(k/3), computed directly for accuracy).
struct SeriesConstants {
  double f_ref_hz;
  double base;
  double step;
};

SeriesConstants ConstantsOf(ThirdOctaveSeries series) {
  switch (series) {
    case ThirdOctaveSeries::kBase2From1Hz: return {1.0, 2.0, 1.0 / 3.0};
    case ThirdOctaveSeries::kIecBase2: return {1000.0, 2.0, 1.0 / 3.0};
    case ThirdOctaveSeries::kIecBase10: return {1000.0, 10.0, 1.0 / 10.0};
  }
  DEB_DEMAND(false);
  return {};
}

// Lower edge of band k, f_ref base^(step (k - 1/2)); the upper edge of band k
// is LowerEdge(k + 1), so neighbouring bands share the same double.
double LowerEdge(int index, const SeriesConstants& c) {
  return c.f_ref_hz * std::pow(c.base, c.step * (2.0 * index - 1.0) / 2.0);
}

}  // namespace

ThirdOctaveBand ThirdOctaveBandAt(int index, ThirdOctaveSeries series) {
  const SeriesConstants c = ConstantsOf(series);
  ThirdOctaveBand band;
  band.index = index;
  band.centre_hz = c.f_ref_hz * std::pow(c.base, c.step * index);
  band.lo_hz = LowerEdge(index, c);
  band.hi_hz = LowerEdge(index + 1, c);
  return band;
}

ThirdOctaveBand ThirdOctaveBandNear(double nominal_hz, ThirdOctaveSeries series) {
  if (!std::isfinite(nominal_hz) || nominal_hz <= 0.0) {
    throw InputError("one-third-octave band " + NumberText(nominal_hz) +
                     " Hz is invalid; a band centre must be finite and > 0");
  }
  const SeriesConstants c = ConstantsOf(series);
  const double position = std::log(nominal_hz / c.f_ref_hz) / std::log(c.base) / c.step;
  const ThirdOctaveBand band = ThirdOctaveBandAt(static_cast<int>(std::lround(position)), series);
  const double octaves_off = std::abs(std::log2(nominal_hz / band.centre_hz));
  if (octaves_off > 1.0 / 12.0) {
    const ThirdOctaveBand other =
        ThirdOctaveBandAt(nominal_hz > band.centre_hz ? band.index + 1 : band.index - 1, series);
    throw InputError("one-third-octave band " + NumberText(nominal_hz) + " Hz is not a band centre of series " +
                     ToString(series) + "; nearest centres are " + NumberText(band.centre_hz) + " and " +
                     NumberText(other.centre_hz) + " Hz (a band name must be within 1/12 octave of its centre)");
  }
  return band;
}

std::vector<ThirdOctaveBand> ThirdOctaveBandsBetween(double lowest_nominal_hz, double highest_nominal_hz,
                                                     ThirdOctaveSeries series) {
  const ThirdOctaveBand lowest = ThirdOctaveBandNear(lowest_nominal_hz, series);
  const ThirdOctaveBand highest = ThirdOctaveBandNear(highest_nominal_hz, series);
  if (lowest.index > highest.index) {
    throw InputError("one-third-octave bands: lowest band " + NumberText(lowest_nominal_hz) +
                     " Hz is above highest band " + NumberText(highest_nominal_hz) + " Hz");
  }
  std::vector<ThirdOctaveBand> bands;
  for (int k = lowest.index; k <= highest.index; ++k) bands.push_back(ThirdOctaveBandAt(k, series));
  return bands;
}

}  // namespace deb
