// A PSD known only at tabulated frequencies: a measured floor spectrum, a
// sensor noise curve from a datasheet, the bins of a Welch estimate. Channels
// (columns) are independent, so S_u is diagonal. Between points the PSD is
// either interpolated log-log (straight lines on the usual log-log plot,
// exact for power laws S = a f^p: for curves sampled on a log scale) or held
// constant across each point's bin (for spectral estimates: bin i covers the
// band between the midpoints to its neighbours, so the integral of the PSD is
// exactly sum_i S_i width_i, Parseval's sum of the estimate, and a tone a few
// bins wide keeps its variance). Outside the data range the behaviour is an
// explicit choice (Extrapolation), by default an error, because a budget
// must not silently invent data.
#pragma once

#include <string>
#include <vector>

#include "deb/core/enum_names.h"
#include "deb/core/extrapolation.h"
#include "deb/spectra/spectrum.h"

namespace deb {

// How a tabulated PSD is read between its points.
enum class SpectrumInterpolation {
  kLogLog,  // log S linear in log f (S linear in f where an end is 0)
  kBins,    // S constant over each point's bin (spectral estimates)
};
inline constexpr EnumName<SpectrumInterpolation> kSpectrumInterpolationNames[] = {
    {SpectrumInterpolation::kLogLog, "log-log"}, {SpectrumInterpolation::kBins, "bins"}};
constexpr EnumNames<SpectrumInterpolation> NamesOf(SpectrumInterpolation) { return kSpectrumInterpolationNames; }
// @throws InputError naming the text and listing the allowed values.
inline SpectrumInterpolation ParseSpectrumInterpolation(const std::string& text) {
  return ParseEnum<SpectrumInterpolation>(text, "spectrum interpolation");
}

struct MeasuredSpectrumOptions {
  Extrapolation extrapolation = Extrapolation::kError;
  SpectrumInterpolation interpolation = SpectrumInterpolation::kLogLog;
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
  // kLogLog, for f_hz[i] <= f <= f_hz[i+1], per channel:
  //   both ends > 0: log S linear in log f;
  //   an end is 0:   S linear in f (log-log is undefined there);
  //   the data range is [f_hz.front(), f_hz.back()].
  // kBins: S(f) = psd(i, .) for bin_edges_hz()[i] <= f < bin_edges_hz()[i+1],
  //   the edges midway between points and, at the ends, half a spacing
  //   beyond the first and last point (at least half the first frequency
  //   above 0); the data range is [edges.front(), edges.back()].
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
  SpectrumInterpolation interpolation() const { return options_.interpolation; }
  // The range outside which Extrapolation applies (see the constructor).
  double lo_hz() const { return lo_hz_; }
  double hi_hz() const { return hi_hz_; }
  // kBins: the n + 1 bin edges; empty for kLogLog.
  const std::vector<double>& bin_edges_hz() const { return edges_hz_; }
  // kBins: the bin holding f (lo_hz() <= f <= hi_hz()).
  std::size_t BinOf(double f_hz) const;

  int channels() const override { return static_cast<int>(psd_.cols()); }
  // @throws InputError outside the data range with Extrapolation::kError.
  Eigen::MatrixXcd Csd(double f_hz) const override;
  // @throws InputError outside the data range with Extrapolation::kError.
  Eigen::VectorXd Psd(double f_hz) const override;
  bool IsDiagonal() const override { return true; }
  // kLogLog: every data frequency, so the grid holds every tabulated point
  // and a narrow peak is not stepped over; between points the interpolant is
  // a power law, which the grid's integration rule integrates exactly.
  // kBins: every bin edge, where S jumps (constant between: exact too).
  std::vector<double> BreakpointsHz() const override;
  // [lo_hz(), hi_hz()] with Extrapolation::kError, else unlimited.
  std::optional<FrequencyInterval> DefinedRangeHz() const override {
    if (options_.extrapolation != Extrapolation::kError) return std::nullopt;
    return FrequencyInterval{lo_hz_, hi_hz_};
  }
  std::string Describe() const override;

 private:
  std::vector<double> f_hz_;
  std::vector<double> log_f_;
  std::vector<double> edges_hz_;  // kBins
  double lo_hz_ = 0.0, hi_hz_ = 0.0;
  Eigen::MatrixXd psd_;
  MeasuredSpectrumOptions options_;
};

}  // namespace deb
