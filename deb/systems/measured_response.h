// A frequency response known only at tabulated frequencies: a measured FRF
// (shaker or hammer test, a vendor's transmissibility curve, a model exported
// from another tool as frequency data). Between two points each entry H_ij is
// interpolated in polar form, linearly in log f: log |H| (straight lines on a
// Bode magnitude plot, exact for a power-law roll-off) and the phase unwrapped
// along the data, so a resonance's phase turns smoothly instead of cutting the
// chord between two complex values; where a magnitude is zero, re and im are
// interpolated linearly in f. Outside the data range the behaviour is the
// user's explicit choice (Extrapolation), by default an error.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "deb/core/extrapolation.h"

namespace deb {

class MeasuredResponse {
 public:
  // h[i] (outputs x inputs) is the response at f_hz[i].
  // @throws InputError (naming `origin`) if there are fewer than 2
  //   frequencies, a frequency is not finite and > 0 or not strictly
  //   increasing, the matrices differ in size or are empty, or an entry is not
  //   finite.
  MeasuredResponse(std::vector<double> f_hz, std::vector<Eigen::MatrixXcd> h,
                   Extrapolation extrapolation = Extrapolation::kError, std::string origin = "");

  int inputs() const { return static_cast<int>(h_.front().cols()); }
  int outputs() const { return static_cast<int>(h_.front().rows()); }
  const std::vector<double>& f_hz() const { return f_hz_; }
  const std::vector<Eigen::MatrixXcd>& table() const { return h_; }
  Extrapolation extrapolation() const { return extrapolation_; }
  const std::string& origin() const { return origin_; }

  // H at f_hz: the tabulated value at a data point, else interpolated.
  // @throws InputError outside the data range with Extrapolation::kError.
  Eigen::MatrixXcd At(double f_hz) const;

  // The rows `rows` (0-based, any order).
  MeasuredResponse SelectOutputs(const std::vector<int>& rows) const;

 private:
  std::vector<double> f_hz_, log_f_;
  std::vector<Eigen::MatrixXcd> h_;
  std::vector<Eigen::MatrixXd> log_mag_;  // log |H|, -inf where |H| = 0
  std::vector<Eigen::MatrixXd> phase_;    // arg H, unwrapped along f per entry
  Extrapolation extrapolation_;
  std::string origin_;
};

}  // namespace deb
