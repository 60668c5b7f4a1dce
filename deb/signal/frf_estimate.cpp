#include "deb/signal/frf_estimate.h"

#include <algorithm>

#include "deb/core/error.h"
#include "deb/core/suggest.h"

namespace deb {
namespace {

int ChannelOf(const CsdEstimate& csd, const std::string& name, const char* role) {
  const auto it = std::find(csd.channel_names.begin(), csd.channel_names.end(), name);
  if (it == csd.channel_names.end()) {
    std::string names;
    for (const auto& n : csd.channel_names) names += (names.empty() ? "" : ", ") + n;
    throw InputError(std::string(role) + " '" + name + "'" + DidYouMean(name, csd.channel_names) +
                     " is not a channel of the recording (" + names + ")");
  }
  return static_cast<int>(it - csd.channel_names.begin());
}

}  // namespace

FrfEstimate EstimateFrf(const CsdEstimate& csd, const std::string& input, const std::vector<std::string>& outputs,
                        FrfEstimator estimator) {
  if (outputs.empty()) throw InputError("a frequency response needs at least one output channel");
  const int x = ChannelOf(csd, input, "input");
  FrfEstimate e;
  e.estimator = estimator;
  e.f_hz = csd.f_hz;
  e.input = input;
  e.outputs = outputs;
  e.provenance = csd.provenance;
  const auto bins = static_cast<Eigen::Index>(csd.f_hz.size());
  e.h = Eigen::MatrixXcd::Zero(bins, static_cast<Eigen::Index>(outputs.size()));
  e.coherence = Eigen::MatrixXd::Zero(bins, static_cast<Eigen::Index>(outputs.size()));
  const Eigen::VectorXd sxx = csd.Auto(x);
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    const int y = ChannelOf(csd, outputs[o], "output");
    if (y == x) throw InputError("output '" + outputs[o] + "' is the input channel");
    const Eigen::VectorXcd sxy = csd.Cross(x, y);  // conj(X) Y
    const Eigen::VectorXd syy = csd.Auto(y), gamma2 = csd.Coherence(x, y);
    for (Eigen::Index k = 0; k < bins; ++k) {
      const bool h1 = estimator == FrfEstimator::kH1;
      if (!(h1 ? sxx(k) > 0.0 : std::abs(sxy(k)) > 0.0)) {
        if (o == 0) ++e.empty_bins;
        continue;
      }
      e.h(k, static_cast<Eigen::Index>(o)) = h1 ? sxy(k) / sxx(k) : syy(k) / std::conj(sxy(k));
      e.coherence(k, static_cast<Eigen::Index>(o)) = gamma2(k);
    }
  }
  return e;
}

}  // namespace deb
