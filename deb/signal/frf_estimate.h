// A frequency response estimated from recordings of a system's input and
// outputs (a shaker or hammer test, an excited closed loop): the H1
// estimator of the Welch cross-spectral matrix (welch.h),
//   H1(f) = S_xy(f) / S_xx(f),  S_xy = E[conj(X) Y]  (the Welch pairing),
// unbiased by noise on the outputs (noise on the input biases |H1| low), with
// the magnitude-squared coherence gamma^2 = |S_xy|^2 / (S_xx S_yy) that says
// how much of each output the input explains. Bendat & Piersol, Random Data,
// ch. 9. The table it gives is what a `type: frf` path reads (frf_csv.h).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "deb/signal/spectral_estimate.h"

namespace deb {

struct FrfEstimate {
  std::vector<double> f_hz;          // the Welch bins (from 0 Hz)
  std::string input;                 // channel name
  std::vector<std::string> outputs;  // channel names
  Eigen::MatrixXcd h;                // bins x outputs: H1
  Eigen::MatrixXd coherence;         // bins x outputs: gamma^2 in [0, 1]
  int empty_bins = 0;                // bins where S_xx = 0: H1 and gamma^2 set to 0
  WelchProvenance provenance;
};

// @throws InputError if `input` or an output is not a channel of `csd`, an
//   output is the input, or no output is given.
FrfEstimate H1Estimate(const CsdEstimate& csd, const std::string& input, const std::vector<std::string>& outputs);

}  // namespace deb
