// A frequency response estimated from recordings of a system's input and
// outputs (a shaker or hammer test, an excited closed loop), from the Welch
// cross-spectral matrix (welch.h), S_xy = E[conj(X) Y] (the Welch pairing):
//   H1(f) = S_xy / S_xx   unbiased by noise on the output (input noise biases |H1| low),
//   H2(f) = S_yy / S_yx   unbiased by noise on the input (output noise biases |H2| high),
// with the magnitude-squared coherence gamma^2 = |S_xy|^2 / (S_xx S_yy) =
// H1 / H2, which says how much of each output the input explains. Bendat &
// Piersol, Random Data, ch. 9. The table it gives is what a `type: frf` path
// reads (frf_csv.h).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "deb/core/enum_names.h"
#include "deb/signal/spectral_estimate.h"

namespace deb {

enum class FrfEstimator { kH1, kH2 };
inline constexpr EnumName<FrfEstimator> kFrfEstimatorNames[] = {{FrfEstimator::kH1, "h1"}, {FrfEstimator::kH2, "h2"}};
constexpr EnumNames<FrfEstimator> NamesOf(FrfEstimator) { return kFrfEstimatorNames; }
// @throws InputError naming the text and listing the allowed values.
inline FrfEstimator ParseFrfEstimator(const std::string& text) {
  return ParseEnum<FrfEstimator>(text, "frequency response estimator");
}

struct FrfEstimate {
  FrfEstimator estimator = FrfEstimator::kH1;
  std::vector<double> f_hz;          // the Welch bins (from 0 Hz)
  std::string input;                 // channel name
  std::vector<std::string> outputs;  // channel names
  Eigen::MatrixXcd h;                // bins x outputs: H1 or H2
  Eigen::MatrixXd coherence;         // bins x outputs: gamma^2 in [0, 1]
  int empty_bins = 0;                // bins where S_xx (H1) or S_yx (H2) is 0: H and gamma^2 set to 0
  WelchProvenance provenance;
};

// @throws InputError if `input` or an output is not a channel of `csd`, an
//   output is the input, or no output is given.
FrfEstimate EstimateFrf(const CsdEstimate& csd, const std::string& input, const std::vector<std::string>& outputs,
                        FrfEstimator estimator = FrfEstimator::kH1);

}  // namespace deb
