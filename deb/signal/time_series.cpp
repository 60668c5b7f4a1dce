#include "deb/signal/time_series.h"

#include <cmath>
#include <set>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/core/suggest.h"

namespace deb {

TimeSeries::TimeSeries(double rate_hz, Eigen::MatrixXd samples, std::vector<std::string> channel_names,
                       std::string unit, std::string origin)
    : rate_hz_(rate_hz),
      samples_(std::move(samples)),
      channel_names_(std::move(channel_names)),
      unit_(std::move(unit)),
      origin_(std::move(origin)) {
  const std::string where = "time series" + (origin_.empty() ? std::string() : " '" + origin_ + "'") + ": ";
  if (!std::isfinite(rate_hz_) || rate_hz_ <= 0.0)
    throw InputError(where + "sample rate " + NumberText(rate_hz_) + " Hz is invalid; it must be finite and > 0");
  if (samples_.rows() < 1 || samples_.cols() < 1)
    throw InputError(where + std::to_string(samples_.rows()) + " samples x " + std::to_string(samples_.cols()) +
                     " channels; at least one sample of one channel is needed");
  if (channel_names_.empty()) {
    for (Eigen::Index c = 0; c < samples_.cols(); ++c) channel_names_.push_back("ch" + std::to_string(c + 1));
  }
  if (static_cast<Eigen::Index>(channel_names_.size()) != samples_.cols())
    throw InputError(where + std::to_string(channel_names_.size()) + " channel names for " +
                     std::to_string(samples_.cols()) + " channels");
  std::set<std::string> seen;
  for (const std::string& name : channel_names_) {
    if (name.empty()) throw InputError(where + "a channel name is empty");
    if (!seen.insert(name).second) throw InputError(where + "channel name '" + name + "' is repeated");
  }
  for (Eigen::Index c = 0; c < samples_.cols(); ++c) {
    const double* x = samples_.col(c).data();
    for (Eigen::Index n = 0; n < samples_.rows(); ++n) {
      if (!std::isfinite(x[n]))
        throw InputError(where + "channel '" + channel_names_[static_cast<std::size_t>(c)] + "', sample " +
                         std::to_string(n) + " (t = " + NumberText(static_cast<double>(n) / rate_hz_) +
                         " s) is " + NumberText(x[n]) + "; every sample must be finite");
    }
  }
}

int TimeSeries::ChannelIndex(const std::string& name) const {
  for (std::size_t c = 0; c < channel_names_.size(); ++c) {
    if (channel_names_[c] == name) return static_cast<int>(c);
  }
  std::string have;
  for (const auto& n : channel_names_) have += (have.empty() ? "" : ", ") + n;
  throw InputError("time series" + (origin_.empty() ? std::string() : " '" + origin_ + "'") + ": no channel '" +
                   name + "'" + DidYouMean(name, channel_names_) + " (channels: " + have + ")");
}

TimeSeries TimeSeries::Select(const std::vector<std::string>& names) const {
  Eigen::MatrixXd picked(samples_.rows(), static_cast<Eigen::Index>(names.size()));
  for (std::size_t j = 0; j < names.size(); ++j) picked.col(static_cast<Eigen::Index>(j)) = samples_.col(ChannelIndex(names[j]));
  return TimeSeries(rate_hz_, std::move(picked), names, unit_, origin_);
}

}  // namespace deb
