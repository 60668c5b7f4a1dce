// A stationary random source, described by its one-sided cross-spectral
// density matrix S_u(f) (channels x channels, Hermitian, positive
// semi-definite), in unit^2/Hz of the source's unit. Every source kind (flat
// noise, vibration criteria, measured data, multi-channel compositions)
// implements this interface; conventions (two-sided input, ASD input, unit
// scale) are converted once, when the source is built.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "deb/core/frequency_interval.h"

namespace deb {

// A sinusoid at f_hz on the source's channels: the complex RMS amplitude on
// each (|rms| the RMS, arg the phase; the variance of channel j is |rms_j|^2).
// Tones at one frequency on several channels are coherent (their phases
// matter); tones at different frequencies are uncorrelated.
struct SpectralLine {
  double f_hz = 0.0;
  Eigen::VectorXcd rms;
};

class Spectrum {
 public:
  virtual ~Spectrum() = default;

  virtual int channels() const = 0;

  // S_u(f) at f_hz > 0. Must be thread-safe (called concurrently).
  virtual Eigen::MatrixXcd Csd(double f_hz) const = 0;

  // Diagonal of S_u(f): the auto-PSD of each channel.
  virtual Eigen::VectorXd Psd(double f_hz) const = 0;

  // True when the channels are uncorrelated at every frequency (S_u diagonal),
  // which lets propagation use sum_k |H_ik|^2 S_kk.
  virtual bool IsDiagonal() const = 0;

  // Frequencies [Hz] where S_u has a jump or a corner (band edges, band
  // limits). The automatic grid places points just either side of each.
  virtual std::vector<double> BreakpointsHz() const { return {}; }

  // If S_u(f) is the same real matrix at every frequency (white noise without
  // band limits), that matrix (one-sided). Enables exact Lyapunov variance.
  virtual std::optional<Eigen::MatrixXd> WhiteLevel() const { return std::nullopt; }

  // The frequencies outside which Csd/Psd throw: tabulated data whose
  // extrapolation is an error. nullopt: defined at every f > 0. The
  // automatic grid stays inside it, and a grid that leaves it is rejected
  // before anything is computed.
  virtual std::optional<FrequencyInterval> DefinedRangeHz() const { return std::nullopt; }

  // Sinusoids in addition to the density (tonal sources, tone_spectrum.h):
  // no PSD on any grid, propagated exactly at their frequencies.
  virtual std::vector<SpectralLine> Lines() const { return {}; }
  // One line for `deb check` and reports, e.g. "VC-D, 23 third-octave bands 0.5-80 Hz".
  virtual std::string Describe() const = 0;
};

}  // namespace deb
