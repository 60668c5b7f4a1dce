// What a spectral estimate from measured data is, beside its numbers: the
// settings that made it and the statistics that say how far to trust it
// (window, segment length, overlap, number of averages, equivalent noise
// bandwidth, resolution, degrees of freedom, chi-square confidence bounds).
// PsdEstimate holds auto-spectra; CsdEstimate the full cross-spectral matrix.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "deb/core/enum_names.h"
#include "deb/signal/window.h"
#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/tabulated_csd.h"

namespace deb {

// Removed from each segment before windowing.
enum class Detrend { kNone, kMean, kLinear };
inline constexpr EnumName<Detrend> kDetrendNames[] = {
    {Detrend::kNone, "none"}, {Detrend::kMean, "mean"}, {Detrend::kLinear, "linear"},
    {Detrend::kMean, "constant", kAlias}};
constexpr EnumNames<Detrend> NamesOf(Detrend) { return kDetrendNames; }
inline Detrend ParseDetrend(const std::string& text) { return ParseEnum<Detrend>(text, "detrend"); }

// How the segments' periodograms are combined.
enum class Averaging { kMean, kMedian };
inline constexpr EnumName<Averaging> kAveragingNames[] = {{Averaging::kMean, "mean"}, {Averaging::kMedian, "median"}};
constexpr EnumNames<Averaging> NamesOf(Averaging) { return kAveragingNames; }
inline Averaging ParseAveraging(const std::string& text) { return ParseEnum<Averaging>(text, "averaging"); }

struct WelchProvenance {
  WindowKind window = WindowKind::kHann;
  int segment_length = 0;   // L, samples
  int overlap_samples = 0;  // samples shared by neighbouring segments
  int segments = 0;         // K, number of averages
  Detrend detrend = Detrend::kMean;
  Averaging averaging = Averaging::kMean;
  double rate_hz = 0.0;
  double resolution_hz = 0.0;   // bin spacing fs / L
  double enbw_hz = 0.0;         // equivalent noise bandwidth fs S2 / S1^2
  double degrees_of_freedom = 0.0;  // nu of the chi-square law of each bin
  double confidence = 0.0;      // level of the bounds, e.g. 0.95
  double lower_factor = 0.0;    // S >= lower_factor P with that confidence
  double upper_factor = 0.0;    // S <= upper_factor P
  // Lines for file headers and reports (no leading '#').
  std::vector<std::string> Describe() const;
};

struct PsdEstimate {
  std::vector<double> f_hz;  // k fs / L, k = 0 .. L/2 (starts at 0 Hz)
  Eigen::MatrixXd psd;       // bins x channels, one-sided, unit^2/Hz
  std::vector<std::string> channel_names;
  std::string unit;          // of the signal; "" if undeclared
  WelchProvenance provenance;
};

struct CsdEstimate {
  std::vector<double> f_hz;
  int channels = 0;
  // bins x channels^2; column i + channels j holds S_ij (see welch.h for the
  // conjugation order). Hermitian: S_ji = conj(S_ij), S_ii real.
  Eigen::MatrixXcd csd;
  std::vector<std::string> channel_names;
  std::string unit;
  WelchProvenance provenance;

  Eigen::VectorXcd Cross(int i, int j) const { return csd.col(i + channels * j); }
  Eigen::VectorXd Auto(int i) const { return csd.col(i + channels * i).real(); }
  // Magnitude-squared coherence |S_ij|^2 / (S_ii S_jj), in [0, 1]; 0 where an
  // auto-spectrum is 0.
  Eigen::VectorXd Coherence(int i, int j) const;
  // The auto-spectra alone.
  PsdEstimate AutoSpectra() const;
};

// The estimate as a budget source: the 0 Hz bin is dropped (a spectrum is
// defined for f > 0). @throws InputError if fewer than 2 bins remain.
std::shared_ptr<const MeasuredSpectrum> ToMeasuredSpectrum(const PsdEstimate& estimate,
                                                           Extrapolation extrapolation = Extrapolation::kError);

// The full estimate as a budget source, in deb's orientation (S_ab =
// E[U_a U_b^*], the conjugate of CsdEstimate's Welch pairing); the 0 Hz bin is
// dropped. @throws InputError if fewer than 2 bins remain, or the estimate
// is median-averaged with more than one channel (its matrix need not be
// positive semi-definite), or the table breaks TabulatedCsd's rules.
std::shared_ptr<const TabulatedCsd> ToTabulatedCsd(const CsdEstimate& estimate,
                                                   Extrapolation extrapolation = Extrapolation::kError);

}  // namespace deb
