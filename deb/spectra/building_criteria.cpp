#include "deb/spectra/building_criteria.h"

#include <cmath>
#include <cstdio>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/spectra/vc_curve.h"

namespace deb {
namespace {

bool Covers(const BuildingCriterion& c, const ThirdOctaveBand& band, const ClassifyOptions& options) {
  const int lo = ThirdOctaveBandNear(c.lowest_band_hz, options.series).index;
  const int hi = ThirdOctaveBandNear(c.highest_band_hz, options.series).index;
  if (band.index > hi) return false;
  return band.index >= lo || (c.extendable && options.low_frequency_extension);
}

bool Meets(double rms, const BuildingCriterion& c, double tolerance) {
  return rms <= c.velocity_um_s * (1.0 + tolerance);
}

}  // namespace

std::vector<BuildingCriterion> BuildingCriteria(CriteriaSet set) {
  std::vector<BuildingCriterion> list;
  if (set != CriteriaSet::kVc) {
    for (const IsoBuildingCriterion& row : IsoBuildingCriteria())
      list.push_back({row.name, row.velocity_um_s, row.lowest_band_hz, row.highest_band_hz, false});
  }
  if (set != CriteriaSet::kIso) {
    for (const VcCriterion& row : VcCriteria())
      list.push_back({row.name, row.velocity_um_s, row.lowest_band_hz, row.highest_band_hz, true});
  }
  return list;
}

Classification Classify(const std::vector<BandRms>& bands_um_s, const ClassifyOptions& options) {
  if (!std::isfinite(options.tolerance) || options.tolerance < 0.0)
    throw InputError("classification tolerance " + NumberText(options.tolerance) + " must be finite and >= 0");
  Classification r;
  r.criteria = BuildingCriteria(options.set);
  const std::size_t n = r.criteria.size();
  for (const BandRms& b : bands_um_s) {
    BandVerdict v;
    v.band = b;
    for (std::size_t c = 0; c < n; ++c) {
      if (!Covers(r.criteria[c], b.band, options)) continue;
      v.assessed = true;
      if (Meets(b.rms, r.criteria[c], options.tolerance)) v.best = c;  // later = more stringent
    }
    r.bands.push_back(v);
  }
  for (std::size_t c = n; c-- > 0;) {
    bool covers_any = false, all_met = true;
    for (const BandVerdict& v : r.bands) {
      if (!Covers(r.criteria[c], v.band.band, options)) continue;
      covers_any = true;
      all_met = all_met && Meets(v.band.rms, r.criteria[c], options.tolerance);
    }
    if (covers_any && all_met) {
      r.overall = c;
      break;
    }
  }
  for (std::size_t i = 0; i < r.bands.size(); ++i) {
    const BandVerdict& v = r.bands[i];
    const bool counts = r.overall ? Covers(r.criteria[*r.overall], v.band.band, options) : v.assessed;
    if (counts && (!r.limiting_band || v.band.rms > r.bands[*r.limiting_band].band.rms)) r.limiting_band = i;
  }
  return r;
}

std::string Classification::Summary() const {
  if (!limiting_band) return "no band is covered by any criterion";
  const BandVerdict& v = bands[*limiting_band];
  char text[256];
  if (overall) {
    const BuildingCriterion& c = criteria[*overall];
    std::snprintf(text, sizeof text, "%s; limiting band %.4g Hz at %.4g um/s RMS (%s: %.4g um/s)", c.name.c_str(),
                  v.band.band.centre_hz, v.band.rms, c.name.c_str(), c.velocity_um_s);
  } else {
    const BuildingCriterion& c = criteria.front();
    std::snprintf(text, sizeof text, "none met; limiting band %.4g Hz at %.4g um/s RMS exceeds %s (%.4g um/s)",
                  v.band.band.centre_hz, v.band.rms, c.name.c_str(), c.velocity_um_s);
  }
  return text;
}

SpectrumClasses ClassifySpectrum(const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                                 SpectrumInterpolation interpolation, const SpectrumClassOptions& options) {
  const ThirdOctaveSeries series = options.classify.series;
  SpectrumClasses out;
  for (Eigen::Index c = 0; c < psd.cols(); ++c) {
    std::vector<double> column(f_hz.size());
    for (std::size_t k = 0; k < column.size(); ++k)
      column[k] = psd(static_cast<Eigen::Index>(k), c) * (options.to_velocity_psd ? options.to_velocity_psd(f_hz[k]) : 1.0);
    out.bands.push_back(options.lowest_hz > 0.0
                            ? ThirdOctaveBandRms(f_hz, column, series, options.lowest_hz, options.highest_hz, interpolation)
                            : ThirdOctaveBandRms(f_hz, column, series, interpolation));
    if (options.classify_bands) out.classes.push_back(Classify(out.bands.back(), options.classify));
  }
  return out;
}

}  // namespace deb

