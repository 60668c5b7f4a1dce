#include "deb/spectra/channel_set.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

// 1-based, as a user counts rows and columns of a matrix in a budget file.
std::string Entry(Eigen::Index i, Eigen::Index j) {
  return "coherence(row " + std::to_string(i + 1) + ", column " + std::to_string(j + 1) + ")";
}

}  // namespace

IndependentChannels::IndependentChannels(std::vector<std::shared_ptr<const Spectrum>> parts)
    : parts_(std::move(parts)) {
  if (parts_.empty()) throw InputError("independent channels: no spectra given; at least one is needed");
  for (const auto& part : parts_) {
    DEB_DEMAND(part != nullptr);
    channels_ += part->channels();
  }
}

Eigen::MatrixXcd IndependentChannels::Csd(double f_hz) const {
  Eigen::MatrixXcd csd = Eigen::MatrixXcd::Zero(channels_, channels_);
  int offset = 0;
  for (const auto& part : parts_) {
    const int n = part->channels();
    csd.block(offset, offset, n, n) = part->Csd(f_hz);
    offset += n;
  }
  return csd;
}

Eigen::VectorXd IndependentChannels::Psd(double f_hz) const {
  Eigen::VectorXd psd(channels_);
  int offset = 0;
  for (const auto& part : parts_) {
    const int n = part->channels();
    psd.segment(offset, n) = part->Psd(f_hz);
    offset += n;
  }
  return psd;
}

bool IndependentChannels::IsDiagonal() const {
  return std::all_of(parts_.begin(), parts_.end(), [](const auto& part) { return part->IsDiagonal(); });
}

std::vector<double> IndependentChannels::BreakpointsHz() const {
  std::vector<double> all;
  for (const auto& part : parts_) {
    const std::vector<double> own = part->BreakpointsHz();
    all.insert(all.end(), own.begin(), own.end());
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

std::optional<FrequencyInterval> IndependentChannels::DefinedRangeHz() const {
  std::optional<FrequencyInterval> range;
  for (const auto& part : parts_) range = Intersect(range, part->DefinedRangeHz());
  return range;
}

std::optional<Eigen::MatrixXd> IndependentChannels::WhiteLevel() const {
  Eigen::MatrixXd level = Eigen::MatrixXd::Zero(channels_, channels_);
  int offset = 0;
  for (const auto& part : parts_) {
    const auto own = part->WhiteLevel();
    if (!own) return std::nullopt;
    const int n = part->channels();
    level.block(offset, offset, n, n) = *own;
    offset += n;
  }
  return level;
}

std::string IndependentChannels::Describe() const {
  const std::string first = parts_.front()->Describe();
  const bool all_same = std::all_of(parts_.begin(), parts_.end(),
                                    [&](const auto& part) { return part->Describe() == first; });
  if (all_same && parts_.size() > 1) {
    return std::to_string(parts_.size()) + " independent copies of [" + first + "]";
  }
  std::string text = std::to_string(channels_) + " independent channels:";
  for (const auto& part : parts_) text += " [" + part->Describe() + "]";
  return text;
}

CorrelatedChannels::CorrelatedChannels(std::shared_ptr<const Spectrum> base, Eigen::MatrixXd coherence)
    : base_(std::move(base)), coherence_(std::move(coherence)) {
  DEB_DEMAND(base_ != nullptr);
  const std::string where = "correlated channels: ";
  if (!base_->IsDiagonal()) {
    throw InputError(where + "the base spectrum [" + base_->Describe() +
                     "] already has cross terms; coherence applies to independent channels only");
  }
  const Eigen::Index n = base_->channels();
  if (coherence_.rows() != n || coherence_.cols() != n) {
    throw InputError(where + "coherence matrix is " + std::to_string(coherence_.rows()) + " x " +
                     std::to_string(coherence_.cols()) + "; the base has " + std::to_string(n) +
                     " channels, so it must be " + std::to_string(n) + " x " + std::to_string(n));
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const double rho = coherence_(i, j);
      if (!std::isfinite(rho)) {
        throw InputError(where + Entry(i, j) + " = " + NumberText(rho) + " is not finite");
      }
      if (i == j && std::abs(rho - 1.0) > kTolerance) {
        throw InputError(where + Entry(i, j) + " = " + NumberText(rho) +
                         "; a channel is fully coherent with itself, the diagonal must be 1");
      }
      if (std::abs(rho - coherence_(j, i)) > kTolerance) {
        throw InputError(where + Entry(i, j) + " = " + NumberText(rho) + " differs from " + Entry(j, i) +
                         " = " + NumberText(coherence_(j, i)) + "; the matrix must be symmetric");
      }
      if (std::abs(rho) > 1.0 + kTolerance) {
        throw InputError(where + Entry(i, j) + " = " + NumberText(rho) + "; coherences must lie in [-1, 1]");
      }
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(coherence_);
  const double smallest = eigen.eigenvalues()(0);
  if (smallest < -kTolerance) {
    // The channels carrying the offending eigenvector: the inconsistent set.
    const Eigen::VectorXd v = eigen.eigenvectors().col(0).cwiseAbs();
    std::string involved;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (v(i) >= 0.1 * v.maxCoeff()) involved += (involved.empty() ? "" : ", ") + std::to_string(i + 1);
    }
    throw InputError(where + "coherence matrix is not positive semi-definite: eigenvalue " +
                     NumberText(smallest) + " < 0 (eigenvector on channels " + involved +
                     "); no set of signals has these coherences together");
  }
}

Eigen::MatrixXd CorrelatedChannels::Correlate(const Eigen::VectorXd& psd) const {
  const Eigen::VectorXd amplitude = psd.cwiseMax(0.0).cwiseSqrt();
  return coherence_.cwiseProduct(amplitude * amplitude.transpose());
}

Eigen::MatrixXcd CorrelatedChannels::Csd(double f_hz) const {
  return Correlate(base_->Psd(f_hz)).cast<std::complex<double>>();
}

bool CorrelatedChannels::IsDiagonal() const {
  const Eigen::Index n = coherence_.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      if (i != j && coherence_(i, j) != 0.0) return false;
    }
  }
  return true;
}

std::optional<Eigen::MatrixXd> CorrelatedChannels::WhiteLevel() const {
  const auto level = base_->WhiteLevel();
  if (!level) return std::nullopt;
  return Correlate(level->diagonal());
}

std::string CorrelatedChannels::Describe() const {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < coherence_.rows(); ++i) {
    for (Eigen::Index j = 0; j < i; ++j) largest = std::max(largest, std::abs(coherence_(i, j)));
  }
  return std::to_string(channels()) + " correlated channels (largest |coherence| " + NumberText(largest) +
         ") of [" + base_->Describe() + "]";
}

}  // namespace deb
