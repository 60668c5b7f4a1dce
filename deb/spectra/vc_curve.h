// Floor vibration given as a vibration criterion (VC) class. A VC curve is a
// one-third-octave band RMS velocity v_VC, not a PSD; a budget needs a PSD,
// so band i becomes the constant PSD v_VC^2 / B_i over [f_c G^(-1/6),
// f_c G^(1/6)) with bandwidth B_i = f_c (G^(1/6) - G^(-1/6)); the band
// integral then returns v_VC^2 exactly (docs/method.md, convention 5; Nizamoglu 2015
// eq. 4-2). The PSD is zero outside the covered bands and is in (um/s)^2/Hz.
//
// Levels and sources: spectra/vc_curves.csv (Gordon 1991, Amick et al. 2005),
// compiled in as VcCriteria(). Default curve: the 8 Hz to 80 Hz bands, where
// every published version is constant velocity; low_frequency_extension
// continues the constant velocity to lower bands (the thesis' "modified VC"
// uses 0.5 Hz to 80 Hz: 23 bands, VcOptions::ThesisModified()).
#pragma once

#include <vector>

#include "deb/core/enum_names.h"
#include "deb/spectra/spectrum.h"
#include "deb/spectra/third_octave.h"

namespace deb {

enum class VcClass { kA, kB, kC, kD, kE, kF, kG };

// The names of VcCriteria() (tests/spectra/vc_curve_test.cpp compares them).
inline constexpr EnumName<VcClass> kVcClassNames[] = {
    {VcClass::kA, "VC-A"}, {VcClass::kB, "VC-B"}, {VcClass::kC, "VC-C"}, {VcClass::kD, "VC-D"},
    {VcClass::kE, "VC-E"}, {VcClass::kF, "VC-F"}, {VcClass::kG, "VC-G"}};
// Parsing accepts any letter case ("vc-d").
constexpr EnumNames<VcClass> NamesOf(VcClass) { return {kVcClassNames, NameCase::kIgnore}; }
// @throws InputError listing allowed values.
inline VcClass ParseVcClass(const std::string& text) { return ParseEnum<VcClass>(text, "vibration criterion"); }

// One row of spectra/vc_curves.csv.
struct VcCriterion {
  VcClass vc_class;
  const char* name;         // "VC-D"
  double velocity_um_s;     // RMS per one-third-octave band
  double velocity_uin_s;    // imperial value printed by the source (informative)
  double lowest_band_hz;    // nominal centre, lowest band of the default curve
  double highest_band_hz;   // nominal centre, highest band of the default curve
  const char* source;       // "G91" or "A05", see the data file
};

// The compiled table, VC-A to VC-G in order (deb/spectra/vc_table.cpp).
const std::vector<VcCriterion>& VcCriteria();
const VcCriterion& VcCriterionOf(VcClass vc_class);

struct VcOptions {
  // Nominal centres of the lowest and highest band. Both must lie inside the
  // class' tabulated range (8-80 Hz) unless low_frequency_extension is set,
  // which allows a lowest band below it (constant velocity continued down).
  double lowest_band_hz = 8.0;
  double highest_band_hz = 80.0;
  bool low_frequency_extension = false;
  ThirdOctaveSeries series = ThirdOctaveSeries::kBase2From1Hz;

  // Nizamoglu (2015) section 4-1: 0.5 Hz to 80 Hz, base-2 centres from 1 Hz
  // (its Table 4-1), constant velocity throughout.
  static VcOptions ThesisModified();
};

class VcSpectrum final : public Spectrum {
 public:
  // The PSD is in (kUnit)^2/Hz.
  static constexpr const char* kUnit = "um/s";

  // @throws InputError if a band is not a band name of options.series, the
  //   highest band is above the class' range, the lowest band is below it
  //   without low_frequency_extension, or lowest > highest.
  explicit VcSpectrum(VcClass vc_class, const VcOptions& options = {});
  // A criterion of any band RMS velocity (> 0, finite), on the bands every
  // class shares (8-80 Hz, extended as above): a tolerance study's or an
  // optimiser's floor level. Named after a class whose velocity it is
  // (to 1e-9), as that class' curve; the same errors.
  VcSpectrum(double velocity_um_s, const VcOptions& options);

  // The class named, or for a velocity the class whose velocity it is
  // (else the band range's class, VC-A).
  VcClass vc_class() const { return vc_class_; }
  double velocity_um_s() const { return velocity_um_s_; }
  const VcOptions& options() const { return options_; }
  const std::vector<ThirdOctaveBand>& bands() const { return bands_; }
  // PSD in band i, (um/s)^2/Hz: velocity_um_s^2 / bands()[i].BandwidthHz().
  const std::vector<double>& band_psd() const { return band_psd_; }

  int channels() const override { return 1; }
  Eigen::MatrixXcd Csd(double f_hz) const override;
  Eigen::VectorXd Psd(double f_hz) const override;
  bool IsDiagonal() const override { return true; }
  // Every band edge (the PSD jumps at each).
  std::vector<double> BreakpointsHz() const override;
  std::string Describe() const override;

 private:
  // Bands are half-open [lo, hi): a frequency on a shared edge belongs to the
  // upper band, and the top edge itself is outside.
  double PsdAt(double f_hz) const;

  void Build(const VcCriterion& range);

  VcClass vc_class_;
  bool named_ = true;  // a class's curve, not a velocity that is none
  VcOptions options_;
  double velocity_um_s_;
  std::vector<ThirdOctaveBand> bands_;
  std::vector<double> band_psd_;
  std::vector<double> edges_hz_;  // bands_.size() + 1 increasing edges
};

}  // namespace deb
