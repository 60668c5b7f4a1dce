// A PSD known only at tabulated frequencies: a measured floor spectrum, a
// sensor noise curve from a datasheet. Channels (columns) are independent, so
// S_u is diagonal. Between points the PSD is interpolated log-log (straight
// lines on the usual log-log plot, exact for power laws S = a f^p); outside
// the data range the behaviour is an explicit choice (Extrapolation), by
// default an error, because a budget must not silently invent data.
#pragma once

#include <string>
#include <vector>

#include "deb/core/extrapolation.h"
#include "deb/spectra/spectrum.h"

namespace deb {

struct MeasuredSpectrumOptions {
  Extrapolation extrapolation = Extrapolation::kError;
  // One name per channel; empty means "ch1", "ch2", ...
  std::vector<std::string> channel_names;
  // Unit of the quantity whose PSD this is (PSD in unit^2/Hz); "" if undeclared.
  std::string unit;
  // Where the data came from (a file name), for messages and Describe().
  std::string origin;
};

class MeasuredSpectrum final : public Spectrum {
 public:
  // psd(i, c): one-sided PSD of channel c at f_hz[i].
  // Interpolation for f_hz[i] <= f <= f_hz[i+1], per channel:
  //   both ends > 0: log S linear in log f;
  //   an end is 0:   S linear in f (log-log is undefined there).
  // @throws InputError if there are fewer than 2 frequencies, a frequency is
  //   not finite and > 0 or not strictly increasing, psd has a different row
  //   count or no column, a PSD value is not finite or negative, or the
  //   number of channel names does not match.
  MeasuredSpectrum(std::vector<double> f_hz, Eigen::MatrixXd psd, MeasuredSpectrumOptions options = {});

  const std::vector<double>& f_hz() const { return f_hz_; }
  const Eigen::MatrixXd& psd_table() const { return psd_; }
  const std::vector<std::string>& channel_names() const { return options_.channel_names; }
  const std::string& unit() const { return options_.unit; }
  Extrapolation extrapolation() const { return options_.extrapolation; }

  int channels() const override { return static_cast<int>(psd_.cols()); }
  // @throws InputError outside the data range with Extrapolation::kError.
  Eigen::MatrixXcd Csd(double f_hz) const override;
  // @throws InputError outside the data range with Extrapolation::kError.
  Eigen::VectorXd Psd(double f_hz) const override;
  bool IsDiagonal() const override { return true; }
  // Every data frequency: the grid then holds every tabulated point, so a
  // narrow peak (a machine tone in a Welch estimate) is not stepped over, and
  // between points the log-log interpolant is a power law, which the grid's
  // integration rule integrates exactly.
  std::vector<double> BreakpointsHz() const override;
  std::string Describe() const override;

 private:
  std::vector<double> f_hz_;
  std::vector<double> log_f_;
  Eigen::MatrixXd psd_;
  MeasuredSpectrumOptions options_;
};

}  // namespace deb
