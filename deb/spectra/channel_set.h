// Multi-channel sources built from simpler ones. Floor motion in x, y, z or
// the noise of seven geophones are several channels of one source; they are
// either independent (diagonal S_u, IndependentChannels) or share a common
// cause (one floor under four isolators, shared electronics), which a
// coherence matrix rho describes (CorrelatedChannels):
//   S_ij(f) = rho_ij sqrt(S_ii(f) S_jj(f)).
// Breakpoints and white levels pass through, so the budget keeps its exact
// Lyapunov path and its grid refinement for composed sources.
#pragma once

#include <memory>
#include <vector>

#include "deb/spectra/spectrum.h"

namespace deb {

// Parts side by side, mutually uncorrelated: S_u = blockdiag(S_1, S_2, ...).
// Channel count = sum of the parts' channel counts.
class IndependentChannels final : public Spectrum {
 public:
  // @throws InputError if parts is empty. Null parts are a bug (DEB_DEMAND).
  explicit IndependentChannels(std::vector<std::shared_ptr<const Spectrum>> parts);

  const std::vector<std::shared_ptr<const Spectrum>>& parts() const { return parts_; }

  int channels() const override { return channels_; }
  Eigen::MatrixXcd Csd(double f_hz) const override;
  Eigen::VectorXd Psd(double f_hz) const override;
  // True when every part is diagonal.
  bool IsDiagonal() const override;
  // Sorted union of the parts' breakpoints.
  std::vector<double> BreakpointsHz() const override;
  // Where every part is defined.
  std::optional<FrequencyInterval> DefinedRangeHz() const override;
  // blockdiag of the parts' levels when every part is white.
  std::optional<Eigen::MatrixXd> WhiteLevel() const override;
  std::string Describe() const override;

 private:
  std::vector<std::shared_ptr<const Spectrum>> parts_;
  int channels_ = 0;
};

// Channels of a diagonal base made coherent: S_ij = rho_ij sqrt(S_ii S_jj).
// rho is real, symmetric, with unit diagonal, |rho_ij| <= 1 and positive
// semi-definite; then S(f) = D(f) rho D(f) with D = diag(sqrt(S_ii)) is
// positive semi-definite at every f. rho = all ones gives fully coherent
// (rank-1) channels, rho = I gives the base back.
class CorrelatedChannels final : public Spectrum {
 public:
  // Tolerance on symmetry, the unit diagonal, |rho_ij| <= 1 and on the
  // smallest eigenvalue (>= -kTolerance).
  static constexpr double kTolerance = 1e-12;

  // @throws InputError if base is not diagonal, rho is not
  //   channels x channels, or rho is not finite, symmetric, unit-diagonal,
  //   bounded by 1 or positive semi-definite; the message names the entry
  //   (i, j) and its value, or the offending eigenvalue.
  CorrelatedChannels(std::shared_ptr<const Spectrum> base, Eigen::MatrixXd coherence);

  const Spectrum& base() const { return *base_; }
  const Eigen::MatrixXd& coherence() const { return coherence_; }

  int channels() const override { return base_->channels(); }
  Eigen::MatrixXcd Csd(double f_hz) const override;
  Eigen::VectorXd Psd(double f_hz) const override { return base_->Psd(f_hz); }
  // True only when rho has no off-diagonal entry (rho = I).
  bool IsDiagonal() const override;
  std::vector<double> BreakpointsHz() const override { return base_->BreakpointsHz(); }
  std::optional<FrequencyInterval> DefinedRangeHz() const override { return base_->DefinedRangeHz(); }
  // rho o sqrt(d d^T), d = diagonal of the base's white level, if it has one.
  std::optional<Eigen::MatrixXd> WhiteLevel() const override;
  std::string Describe() const override;

 private:
  Eigen::MatrixXd Correlate(const Eigen::VectorXd& psd) const;

  std::shared_ptr<const Spectrum> base_;
  Eigen::MatrixXd coherence_;
};

}  // namespace deb
