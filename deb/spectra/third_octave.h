// One-third-octave bands: the frequency axis of vibration criteria (VC
// curves) and of band-RMS spectra. Band k has centre f_c(k) = f_ref G^(k/3)
// and edges f_c G^(-1/6), f_c G^(+1/6), so adjacent bands share an edge and
// the bandwidth is f_c (G^(1/6) - G^(-1/6)) (about 0.2316 f_c for G = 2).
// Three series are in use and differ by up to 2.4 %, so the choice is explicit:
//  - kBase2From1Hz: f_ref = 1 Hz, G = 2. Centres are 0.5, 0.63, 0.79, 1, 1.26,
//    ..., 64, 80.6 Hz; exactly the centres of Nizamoglu (2015) Table 4-1 (its
//    eq. 4-5, f_{i+1} = 2^(1/3) f_i, from 0.5 Hz), which deb reproduces.
//  - kIecBase2: f_ref = 1000 Hz, G = 2 (IEC 61260-1:2014 base-two exact
//    mid-band frequencies): 0.488, 0.615, ..., 78.7 Hz.
//  - kIecBase10: f_ref = 1000 Hz, G = 10^(3/10) (IEC 61260-1:2014 base-ten,
//    what most analysers use): 0.501, 0.631, ..., 79.4 Hz.
// Bands are named by nominal frequency (0.5, 0.63, 0.8, 1, ..., 80 Hz); a
// nominal value selects the band whose exact centre is nearest (in log f).
#pragma once

#include <string>
#include <vector>

#include "deb/core/enum_names.h"

namespace deb {

enum class ThirdOctaveSeries { kBase2From1Hz, kIecBase2, kIecBase10 };

inline constexpr EnumName<ThirdOctaveSeries> kThirdOctaveSeriesNames[] = {
    {ThirdOctaveSeries::kBase2From1Hz, "base2_1hz"}, {ThirdOctaveSeries::kIecBase2, "iec_base2"},
    {ThirdOctaveSeries::kIecBase10, "iec_base10"}};
constexpr EnumNames<ThirdOctaveSeries> NamesOf(ThirdOctaveSeries) { return kThirdOctaveSeriesNames; }
// @throws InputError naming the text and listing the allowed values.
inline ThirdOctaveSeries ParseThirdOctaveSeries(const std::string& text) {
  return ParseEnum<ThirdOctaveSeries>(text, "one-third-octave series");
}

struct ThirdOctaveBand {
  int index = 0;  // k in f_c = f_ref G^(k/3)
  double centre_hz = 0.0;
  double lo_hz = 0.0;  // f_c G^(-1/6); equal (bit for bit) to hi_hz of band k-1
  double hi_hz = 0.0;  // f_c G^(+1/6)
  double BandwidthHz() const { return hi_hz - lo_hz; }
};

// Band k of a series.
ThirdOctaveBand ThirdOctaveBandAt(int index, ThirdOctaveSeries series);

// The band whose centre is nearest to nominal_hz in log f.
// @throws InputError if nominal_hz is not finite and > 0, or is more than
//   1/12 octave from that centre (it is then not a band name, e.g. 0.56 Hz).
ThirdOctaveBand ThirdOctaveBandNear(double nominal_hz, ThirdOctaveSeries series);

// All bands from the one named lowest_nominal_hz to the one named
// highest_nominal_hz, both included, in increasing frequency.
// @throws InputError as ThirdOctaveBandNear, or if lowest > highest.
std::vector<ThirdOctaveBand> ThirdOctaveBandsBetween(double lowest_nominal_hz,
                                                     double highest_nominal_hz,
                                                     ThirdOctaveSeries series);

}  // namespace deb
