#include "deb/signal/recording.h"

#include "deb/core/at_key_path.h"
#include "deb/signal/spectral_estimate.h"
#include "deb/spectra/scaled_spectrum.h"
#include "deb/units/unit.h"

namespace deb {

TimeSeries ReadRecording(const RecordingSpec& spec) {
  TimeSeries series = [&] {
    if (!spec.raw) {
      TimeSeriesCsvOptions o;
      o.rate_hz = spec.rate_hz;
      o.unit = spec.unit;
      return ReadTimeSeriesCsv(spec.file, o);
    }
    RawTimeSeriesOptions o;
    o.format = *spec.raw;
    o.rate_hz = spec.rate_hz.value_or(0.0);
    o.unit = spec.unit;
    o.channel_names = spec.file_channel_names;
    o.channels = spec.file_channel_names.empty() ? spec.file_channels : static_cast<int>(spec.file_channel_names.size());
    return ReadRawTimeSeries(spec.file, o);
  }();
  return spec.columns.empty() ? series : series.Select(spec.columns);
}

RecordingSpectrum SpectrumFromRecording(const TimeSeries& series, const RecordingSpectrumOptions& options) {
  const bool keep_cross = options.cross_spectra && series.channels() > 1;
  if (keep_cross && options.welch.averaging == Averaging::kMedian)
    throw InputError(options.averaging_key_path,
                     "median averaging does not give a positive semi-definite cross-spectral matrix (real and "
                     "imaginary parts are medianed apart); use averaging: mean, or cross_spectra: none for "
                     "independent channels");
  RecordingSpectrum out;
  if (keep_cross) {
    const CsdEstimate estimate = AtKeyPath(options.key_path, [&] { return WelchCsd(series, options.welch); });
    out.spectrum = AtKeyPath(options.file_key_path, [&] { return ToTabulatedCsd(estimate, options.extrapolation); });
    out.channel_names = estimate.channel_names;
  } else {
    const PsdEstimate estimate = AtKeyPath(options.key_path, [&] { return WelchPsd(series, options.welch); });
    out.spectrum =
        AtKeyPath(options.file_key_path, [&] { return ToMeasuredSpectrum(estimate, options.extrapolation); });
    out.channel_names = estimate.channel_names;
  }
  out.unit = options.unit.empty() ? series.unit() : options.unit;
  if (series.unit().empty()) return out;
  const UnitConversion conv = AtKeyPath(options.unit_key_path, [&] { return ConvertUnit(series.unit(), out.unit); });
  if (!conv.IsPureScale())
    throw InputError(options.unit_key_path, "the file's unit '" + series.unit() + "' and '" + out.unit +
                                                "' are not the same quantity");
  const double factor = conv.scale * conv.scale;
  if (factor != 1.0) out.spectrum = std::make_shared<ScaledSpectrum>(out.spectrum, factor);
  return out;
}

}  // namespace deb
