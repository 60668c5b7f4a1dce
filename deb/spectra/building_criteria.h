// Classification of a measured floor against the generic building vibration
// criteria: the VC curves (vc_curve.h, spectra/vc_curves.csv) and the curves
// derived from ISO 2631-2 for workshops, offices, residences and operating
// theatres (spectra/iso_building_curves.csv). All are limits on the
// one-third-octave band RMS velocity, constant over their band range, so a
// floor "meets" a criterion when every band the criterion covers is at or
// below its level. The answer is given per band (the most stringent
// criterion met there) and overall (the most stringent criterion met in
// every band it covers), with the band that limits the overall class.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "deb/spectra/band_rms.h"
#include "deb/spectra/measured_spectrum.h"

namespace deb {

// One row of spectra/iso_building_curves.csv.
struct IsoBuildingCriterion {
  const char* name;        // "ISO-office"
  double velocity_um_s;    // RMS per one-third-octave band
  double velocity_uin_s;   // imperial value printed by the sources (informative)
  double lowest_band_hz;   // nominal centre
  double highest_band_hz;  // nominal centre
  double iso_factor;       // multiple of the ISO 2631-2 base curve
};

// The compiled table, least stringent first (deb/spectra/iso_building_table.cpp).
const std::vector<IsoBuildingCriterion>& IsoBuildingCriteria();

enum class CriteriaSet { kVc, kIso, kAll };
inline constexpr EnumName<CriteriaSet> kCriteriaSetNames[] = {
    {CriteriaSet::kVc, "vc"}, {CriteriaSet::kIso, "iso"}, {CriteriaSet::kAll, "all"}};
constexpr EnumNames<CriteriaSet> NamesOf(CriteriaSet) { return kCriteriaSetNames; }
// @throws InputError listing the allowed values.
inline CriteriaSet ParseCriteriaSet(const std::string& text) { return ParseEnum<CriteriaSet>(text, "criteria set"); }

struct BuildingCriterion {
  std::string name;
  double velocity_um_s = 0.0;
  double lowest_band_hz = 0.0;   // nominal centre of the lowest band covered
  double highest_band_hz = 0.0;  // nominal centre of the highest band covered
  // The constant velocity may be continued below lowest_band_hz on request
  // (the VC curves, as the thesis' modified VC; not the ISO curves, whose
  // low-frequency shape deb does not tabulate).
  bool extendable = false;
};

// The criteria of a set, least stringent (highest level) first.
std::vector<BuildingCriterion> BuildingCriteria(CriteriaSet set);

struct ClassifyOptions {
  CriteriaSet set = CriteriaSet::kAll;
  ThirdOctaveSeries series = ThirdOctaveSeries::kBase2From1Hz;
  // Apply the extendable criteria to bands below their lowest band as well.
  bool low_frequency_extension = false;
  // A band meets a level when rms <= level (1 + tolerance): the band
  // integral of a spectrum built exactly at a level carries rounding.
  double tolerance = 1e-9;
};

struct BandVerdict {
  BandRms band;                     // rms in um/s
  bool assessed = false;            // some criterion covers this band
  std::optional<std::size_t> best;  // most stringent criterion met (index into criteria)
};

struct Classification {
  std::vector<BuildingCriterion> criteria;  // least stringent first
  std::vector<BandVerdict> bands;
  // Most stringent criterion met in every band it covers (and covering at
  // least one analysed band); none if even the least stringent fails.
  std::optional<std::size_t> overall;
  // The assessed band with the highest RMS among those the overall criterion
  // covers (all assessed bands if none is met): it decides the class.
  std::optional<std::size_t> limiting_band;

  // e.g. "VC-D; limiting band 12.7 Hz at 5.02 um/s RMS (VC-D 6.25 um/s)".
  std::string Summary() const;
};

// bands_um_s: band RMS velocities in um/s of bands of options.series.
// @throws InputError if options.tolerance is negative or not finite.
Classification Classify(const std::vector<BandRms>& bands_um_s, const ClassifyOptions& options = {});

struct SpectrumClassOptions {
  ClassifyOptions classify;  // classify.series also sets the bands when not classifying
  bool classify_bands = true;  // false: band RMS only, in the spectrum's unit
  // Factor taking the PSD at f_hz > 0 to (um/s)^2/Hz (deb/units'
  // UnitConversion::PsdFactor from the spectrum's unit to um/s); empty: 1.
  std::function<double(double f_hz)> to_velocity_psd;
  double lowest_hz = 0.0, highest_hz = 0.0;  // nominal centres of the bands; lowest 0: all bands in the data
};

struct SpectrumClasses {
  std::vector<std::vector<BandRms>> bands;  // per channel: um/s, or the spectrum's unit without classification
  std::vector<Classification> classes;      // per channel; empty without classification
};

// The one-third-octave band RMS of every channel of psd (one-sided, rows
// f_hz, read as `interpolation`), converted to velocity, and its class.
// @throws InputError as ThirdOctaveBandRms and Classify.
SpectrumClasses ClassifySpectrum(const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                                 SpectrumInterpolation interpolation, const SpectrumClassOptions& options);

}  // namespace deb
