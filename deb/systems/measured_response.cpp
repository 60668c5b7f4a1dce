#include "deb/systems/measured_response.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/number_text.h"

namespace deb {

MeasuredResponse::MeasuredResponse(std::vector<double> f_hz, std::vector<Eigen::MatrixXcd> h,
                                   Extrapolation extrapolation, std::string origin)
    : f_hz_(std::move(f_hz)), h_(std::move(h)), extrapolation_(extrapolation), origin_(std::move(origin)) {
  const std::string where = "measured response" + (origin_.empty() ? std::string() : " '" + origin_ + "'") + ": ";
  if (f_hz_.size() < 2) throw InputError(where + "needs at least 2 frequencies, got " + std::to_string(f_hz_.size()));
  if (h_.size() != f_hz_.size())
    throw InputError(where + std::to_string(h_.size()) + " matrices for " + std::to_string(f_hz_.size()) +
                     " frequencies");
  if (h_.front().size() == 0) throw InputError(where + "the response has no entries");
  for (std::size_t i = 0; i < f_hz_.size(); ++i) {
    const double f = f_hz_[i];
    if (!std::isfinite(f) || f <= 0.0)
      throw InputError(where + "frequency " + NumberText(f) + " Hz (point " + std::to_string(i + 1) +
                       ") is not finite and > 0");
    if (i > 0 && !(f > f_hz_[i - 1]))
      throw InputError(where + "frequency " + NumberText(f) + " Hz (point " + std::to_string(i + 1) +
                       ") is not greater than " + NumberText(f_hz_[i - 1]) + " Hz; frequencies must increase strictly");
    if (h_[i].rows() != h_.front().rows() || h_[i].cols() != h_.front().cols())
      throw InputError(where + "point " + std::to_string(i + 1) + " is " + std::to_string(h_[i].rows()) + "x" +
                       std::to_string(h_[i].cols()) + ", the first is " + std::to_string(h_.front().rows()) + "x" +
                       std::to_string(h_.front().cols()));
    if (!h_[i].allFinite())
      throw InputError(where + "a response value at " + NumberText(f) + " Hz is not finite");
  }
  const Eigen::Index p = h_.front().rows(), m = h_.front().cols();
  for (std::size_t i = 0; i < f_hz_.size(); ++i) {
    log_f_.push_back(std::log(f_hz_[i]));
    log_mag_.push_back(h_[i].cwiseAbs().array().log().matrix());
    Eigen::MatrixXd phase(p, m);
    for (Eigen::Index r = 0; r < p; ++r)
      for (Eigen::Index c = 0; c < m; ++c) {
        double a = std::arg(h_[i](r, c));
        if (i > 0) {  // unwrap: the branch nearest the previous point's phase
          const double prev = phase_.back()(r, c);
          a += 2.0 * kPi * std::round((prev - a) / (2.0 * kPi));
        }
        phase(r, c) = a;
      }
    phase_.push_back(std::move(phase));
  }
}

Eigen::MatrixXcd MeasuredResponse::At(double f_hz) const {
  DEB_DEMAND(std::isfinite(f_hz));
  const double first = f_hz_.front(), last = f_hz_.back();
  if (f_hz < first || f_hz > last) {
    switch (extrapolation_) {
      case Extrapolation::kError:
        throw InputError("measured response" + (origin_.empty() ? std::string() : " '" + origin_ + "'") +
                         ": frequency " + NumberText(f_hz) + " Hz is outside the data range " + NumberText(first) + "-" +
                         NumberText(last) +
                         " Hz (extrapolation: error); keep the grid inside the data or choose extrapolation zero "
                         "or hold");
      case Extrapolation::kZero: return Eigen::MatrixXcd::Zero(outputs(), inputs());
      case Extrapolation::kHold: return f_hz < first ? h_.front() : h_.back();
    }
  }
  const auto above = std::upper_bound(f_hz_.begin(), f_hz_.end(), f_hz);
  const std::size_t i1 = std::min(static_cast<std::size_t>(above - f_hz_.begin()), f_hz_.size() - 1);
  const std::size_t i0 = i1 - 1;
  if (f_hz == f_hz_[i0]) return h_[i0];
  if (f_hz == f_hz_[i1]) return h_[i1];
  const double t = (std::log(f_hz) - log_f_[i0]) / (log_f_[i1] - log_f_[i0]);
  const double u = (f_hz - f_hz_[i0]) / (f_hz_[i1] - f_hz_[i0]);
  Eigen::MatrixXcd h(outputs(), inputs());
  for (Eigen::Index c = 0; c < h.cols(); ++c)
    for (Eigen::Index r = 0; r < h.rows(); ++r) {
      const double l0 = log_mag_[i0](r, c), l1 = log_mag_[i1](r, c);
      if (std::isfinite(l0) && std::isfinite(l1)) {
        const double phase = phase_[i0](r, c) + t * (phase_[i1](r, c) - phase_[i0](r, c));
        h(r, c) = std::polar(std::exp(l0 + t * (l1 - l0)), phase);
      } else {
        h(r, c) = h_[i0](r, c) + u * (h_[i1](r, c) - h_[i0](r, c));
      }
    }
  return h;
}

MeasuredResponse MeasuredResponse::SelectOutputs(const std::vector<int>& rows) const {
  std::vector<Eigen::MatrixXcd> h;
  h.reserve(h_.size());
  for (const Eigen::MatrixXcd& hi : h_) {
    Eigen::MatrixXcd s(static_cast<Eigen::Index>(rows.size()), hi.cols());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      DEB_DEMAND(rows[k] >= 0 && rows[k] < hi.rows());
      s.row(static_cast<Eigen::Index>(k)) = hi.row(rows[k]);
    }
    h.push_back(std::move(s));
  }
  return MeasuredResponse(f_hz_, std::move(h), extrapolation_, origin_);
}

}  // namespace deb
