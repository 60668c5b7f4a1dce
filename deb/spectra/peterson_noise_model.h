// Peterson's New Low and New High Noise Models (USGS OFR 93-322, 1993): the
// quietest and noisiest vertical ground acceleration observed worldwide, the
// usual yardstick for a seismometer's self-noise and for how quiet a site
// is. PSD [dB re 1 (m/s^2)^2/Hz] = A + B log10(P) on segments of period P;
// coefficients in spectra/peterson_1993_noise_models.csv, compiled in
// (deb/spectra/peterson_table.cpp). Defined for 1e-5 Hz <= f <= 10 Hz.
#pragma once

#include <string>
#include <vector>

#include "deb/core/enum_names.h"
#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/spectrum.h"

namespace deb {

enum class PetersonModel { kLow, kHigh };
inline constexpr EnumName<PetersonModel> kPetersonModelNames[] = {{PetersonModel::kLow, "nlnm"},
                                                                  {PetersonModel::kHigh, "nhnm"}};
// Parsing accepts any letter case ("NLNM").
constexpr EnumNames<PetersonModel> NamesOf(PetersonModel) { return {kPetersonModelNames, NameCase::kIgnore}; }
inline PetersonModel ParsePetersonModel(const std::string& text) {
  return ParseEnum<PetersonModel>(text, "Peterson noise model");
}

// One row of the data file: valid for period_from_s <= P < period_to_s.
struct PetersonSegment {
  double period_from_s;
  double period_to_s;
  double a_db;
  double b_db;
};

// The model's segments in increasing period.
const std::vector<PetersonSegment>& PetersonSegments(PetersonModel model);

// One-sided vertical acceleration PSD, (m/s^2)^2/Hz.
// @throws InputError if f_hz is outside [1e-5, 10] Hz.
double PetersonAccelerationPsd(PetersonModel model, double f_hz);

// The frequencies at which `deb spectrum reference` tabulates a model:
// kMinHz to kMaxHz (six decades), ceil(6 points_per_decade) + 1 of them,
// evenly spaced in log f.
// @throws InputError unless 1 <= points_per_decade <= limits::kMaxPointsPerDecade.
std::vector<double> PetersonFrequencies(double points_per_decade);

class PetersonSpectrum final : public Spectrum {
 public:
  static constexpr const char* kUnit = "m/s^2";
  static constexpr double kMinHz = 1e-5;
  static constexpr double kMaxHz = 10.0;

  // extrapolation: outside [kMinHz, kMaxHz], as MeasuredSpectrum.
  explicit PetersonSpectrum(PetersonModel model, Extrapolation extrapolation = Extrapolation::kError);

  PetersonModel model() const { return model_; }
  int channels() const override { return 1; }
  Eigen::MatrixXcd Csd(double f_hz) const override;
  Eigen::VectorXd Psd(double f_hz) const override;
  bool IsDiagonal() const override { return true; }
  // 1/P at every segment boundary (the slope changes there).
  std::vector<double> BreakpointsHz() const override;
  // [kMinHz, kMaxHz] with Extrapolation::kError, else unlimited.
  std::optional<FrequencyInterval> DefinedRangeHz() const override {
    if (extrapolation_ != Extrapolation::kError) return std::nullopt;
    return FrequencyInterval{kMinHz, kMaxHz};
  }
  std::string Describe() const override;

 private:
  double PsdAt(double f_hz) const;
  PetersonModel model_;
  Extrapolation extrapolation_;
};

}  // namespace deb
