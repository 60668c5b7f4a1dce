// A uniformly sampled multi-channel recording: floor accelerometers, geophones
// side by side. The value type behind every spectral estimate; it validates
// once, in its constructor, so the estimators can trust it (STYLE rule 5).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace deb {

class TimeSeries {
 public:
  // samples(n, c): sample n of channel c, taken at t = n / rate_hz.
  // Empty channel_names become "ch1", "ch2", ...; unit may be "" (undeclared).
  // @throws InputError if rate_hz is not finite and > 0, there is no sample or
  //   no channel, a sample is not finite (naming channel and sample index),
  //   the number of names differs from the number of channels, or a name is
  //   empty or repeated. origin (a file name) prefixes the messages.
  TimeSeries(double rate_hz, Eigen::MatrixXd samples, std::vector<std::string> channel_names = {},
             std::string unit = "", std::string origin = "");

  double rate_hz() const { return rate_hz_; }
  // Samples x channels, column-major: each channel is contiguous.
  const Eigen::MatrixXd& samples() const { return samples_; }
  Eigen::Index size() const { return samples_.rows(); }
  int channels() const { return static_cast<int>(samples_.cols()); }
  double duration_s() const { return static_cast<double>(size()) / rate_hz_; }
  const std::vector<std::string>& channel_names() const { return channel_names_; }
  const std::string& unit() const { return unit_; }
  const std::string& origin() const { return origin_; }

  // Index of the channel called name. @throws InputError listing the names.
  int ChannelIndex(const std::string& name) const;
  // The named channels, in the order given. @throws InputError as ChannelIndex.
  TimeSeries Select(const std::vector<std::string>& names) const;

 private:
  double rate_hz_;
  Eigen::MatrixXd samples_;
  std::vector<std::string> channel_names_;
  std::string unit_;
  std::string origin_;
};

}  // namespace deb
