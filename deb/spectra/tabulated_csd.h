// A cross-spectral density matrix known only at tabulated frequencies: the
// Welch estimate of a multi-channel recording (floor x, y, z; sensors side by
// side), whose channels are coherent where they share a cause. Unlike
// MeasuredSpectrum it keeps the off-diagonal terms, so S_y = H S_u H^H sees
// the coherence (and the phase) between channels.
//
// Orientation: S_ab(f) pairs E[U_a U_b^*] like the rest of deb (the engine
// forms sum_ab h_a S_ab conj(h_b)); a channel b lagging a by tau has phase
// +2 pi f tau in S_ab. Welch's convention (deb/signal/welch.h) is the
// conjugate: ToTabulatedCsd (deb/signal/spectral_estimate.h) converts.
//
// Between two nodes f0 < f < f1 (t = ln(f/f0) / ln(f1/f0)):
//   - the auto-PSDs S_aa are interpolated as MeasuredSpectrum does (log S
//     linear in log f, or S linear in f where an end is 0);
//   - the coherency C_ab = S_ab / sqrt(S_aa S_bb) (unit diagonal; a channel
//     whose PSD is 0 has no coherency with the others) is interpolated
//     linearly in t, C = (1 - t) C0 + t C1, and
//   - S = D C D with D = diag(sqrt(S_aa)).
// C0 and C1 are positive semi-definite with unit diagonal, so is their convex
// combination, and D C D is a congruence of it: every interpolated matrix is
// Hermitian and positive semi-definite, and the auto-PSDs match the
// diagonal-only MeasuredSpectrum exactly. At a node the table is returned.
// With SpectrumInterpolation::kBins (a Welch estimate) the matrix is instead
// held constant over each node's bin, as MeasuredSpectrum does with the autos.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/spectrum.h"

namespace deb {

struct TabulatedCsdOptions {
  Extrapolation extrapolation = Extrapolation::kError;
  SpectrumInterpolation interpolation = SpectrumInterpolation::kLogLog;
  // One name per channel; empty means "ch1", "ch2", ...
  std::vector<std::string> channel_names;
  // Unit of the signal (CSD in unit^2/Hz); "" if undeclared.
  std::string unit;
  // Where the data came from, for messages and Describe().
  std::string origin;
};

class TabulatedCsd final : public Spectrum {
 public:
  // Relative tolerance of the checks on the table: |Im S_aa| <= tol S_aa,
  // |S_ab - conj(S_ba)| <= tol sqrt(S_aa S_bb), and the smallest eigenvalue
  // of the coherency matrix >= -tol. A Welch mean of outer products meets it
  // to rounding.
  static constexpr double kTolerance = 1e-9;

  // csd(i, a + n b) = S_ab(f_hz[i]), n = channels (the layout of
  // CsdEstimate, in deb's orientation above). Only the diagonal and the
  // upper triangle (a < b) are kept; the lower triangle must agree with it.
  // @throws InputError if there are fewer than 2 frequencies, a frequency is
  //   not finite and > 0 or not strictly increasing, channels < 1, csd is
  //   not f_hz.size() x channels^2, a value is not finite, an auto-PSD is
  //   negative or not real, the matrix is not Hermitian or not positive
  //   semi-definite (naming the frequency, the entry and its value), or the
  //   number of channel names does not match.
  TabulatedCsd(std::vector<double> f_hz, int channels, const Eigen::MatrixXcd& csd, TabulatedCsdOptions options = {});

  const std::vector<double>& f_hz() const { return autos_.f_hz(); }
  const std::vector<std::string>& channel_names() const { return autos_.channel_names(); }
  Extrapolation extrapolation() const { return options_.extrapolation; }

  int channels() const override { return channels_; }
  // @throws InputError outside the data range with Extrapolation::kError.
  Eigen::MatrixXcd Csd(double f_hz) const override;
  // @throws InputError outside the data range with Extrapolation::kError.
  Eigen::VectorXd Psd(double f_hz) const override;
  // False: the table carries cross terms (even if some happen to be 0).
  bool IsDiagonal() const override { return false; }
  // As MeasuredSpectrum: every node (log-log) or every bin edge (bins).
  std::vector<double> BreakpointsHz() const override;
  std::optional<FrequencyInterval> DefinedRangeHz() const override { return autos_.DefinedRangeHz(); }
  std::string Describe() const override;

 private:
  // Column of the upper-triangle pair a < b in cross_.
  Eigen::Index Pair(int a, int b) const;
  // The table at node i as a full Hermitian matrix.
  Eigen::MatrixXcd Node(std::size_t i) const;
  // C_ab = S_ab / sqrt(S_aa S_bb) at node i (0 where an auto-PSD is 0).
  std::complex<double> Coherency(std::size_t i, int a, int b) const;

  // The auto-PSDs: their interpolation, range checks and extrapolation.
  MeasuredSpectrum autos_;
  std::vector<double> log_f_;
  int channels_ = 0;
  Eigen::MatrixXcd cross_;  // nodes x channels (channels - 1) / 2: S_ab, a < b
  TabulatedCsdOptions options_;
};

}  // namespace deb
