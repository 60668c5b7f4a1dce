#include <cstdio>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/report/measurement/measurement_plots.h"
#include "deb/spectra/band_rms.h"
#include "deb/spectra/band_table.h"
#include "deb/spectra/building_criteria.h"
#include "deb/spectra/peterson_noise_model.h"
#include "deb/units/unit.h"
#include "tools/spectrum_subcommands.h"

// The subcommands that read or make spectrum tables: bands, convert and
// reference.
namespace deb::tools {

int RunBands(const Settings& s) {
  const SpectrumCsv csv = ReadSpectrumCsv(s.spectrum_file);
  std::string unit = csv.unit.value_or("");
  if (!s.unit.empty()) {
    if (!unit.empty() && unit != s.unit)
      throw InputError(s.spectrum_file + ": the file declares '# unit: " + unit + "' but --unit " + s.unit +
                       " is given");
    unit = s.unit;
  }
  const bool classify = s.criteria != "none";
  const ThirdOctaveSeries series = ParseThirdOctaveSeries(s.series);
  SpectrumClassOptions options;
  options.classify_bands = classify;
  options.classify.series = series;
  options.classify.low_frequency_extension = s.extend;
  options.lowest_hz = s.lowest_hz;
  options.highest_hz = s.highest_hz;
  if (classify) {
    options.classify.set = ParseCriteriaSet(s.criteria);
    if (unit.empty())
      throw InputError(s.spectrum_file + ": classification needs the unit of the spectrum: give '# unit:' in the "
                       "file or --unit (any velocity, displacement or acceleration unit)");
  }
  // Criteria are band RMS velocities in um/s: convert (with (2 pi f)^2n for
  // displacement or acceleration) before integrating.
  const UnitConversion to_velocity = classify ? ConvertUnit(unit, "um/s") : UnitConversion{};
  if (classify) options.to_velocity_psd = [&to_velocity](double f_hz) { return to_velocity.PsdFactor(f_hz); };
  const std::string band_unit = classify ? "um/s" : unit;
  std::vector<std::string> comments = {"one-third-octave band RMS (" + ToString(series) + " centres)" +
                                       (band_unit.empty() ? "" : " in " + band_unit) + " of " + s.spectrum_file};
  if (classify && !to_velocity.IsPureScale())
    comments.push_back("converted from " + unit + ": " + to_velocity.Describe());
  const SpectrumClasses classes = ClassifySpectrum(csv.f_hz, csv.psd, csv.interpolation, options);
  const std::vector<std::vector<BandRms>>& per_channel = classes.bands;
  const std::vector<Classification>& verdicts = classes.classes;
  Outputs outputs(s);
  outputs.Text(s.out, BandTableText(comments, band_unit, csv.channel_names, classes), "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true)) {
    outputs.Plot(*place, report::BandClassPlot(csv.channel_names, per_channel, verdicts, options.classify, band_unit,
                                               SourceName(s.spectrum_file), place->stem));
  }
  outputs.Write();
  if (!s.out.empty() && s.out != "-") {
    for (std::size_t c = 0; c < per_channel.size(); ++c) {
      std::printf("%s: %zu bands", csv.channel_names[c].c_str(), per_channel[c].size());
      if (classify) std::printf(", %s", verdicts[c].Summary().c_str());
      std::printf("\n");
    }
    // The channels share one frequency grid, so one count holds for all: said once.
    if (const int coarse = CoarseBandCount(per_channel.front()); coarse > 0)
      std::printf("warning: %d band(s) hold fewer than %d spectral lines; use a longer segment to resolve them\n",
                  coarse, kFewLines);
    if (!csv.bound_names.empty())
      std::printf("(%zu confidence-bound column(s) of %s, not channels, are not classified)\n", csv.bound_names.size(),
                  s.spectrum_file.c_str());
  }
  PrintWritten(outputs, s.out);
  return 0;
}

int RunConvert(const Settings& s) {
  if (s.from_bands) {
    // A band table: centre_hz and one band-RMS column per channel.
    // The output of `deb spectrum bands` as it is, or a table by hand (band_table.h).
    const BandTable table = ReadBandTable(s.spectrum_file);
    const ThirdOctaveSeries series = ParseThirdOctaveSeries(s.series);
    const BandTablePsd table_psd = PsdOfBandTable(table, series);
    const std::vector<double>& f_out = table_psd.f_hz;
    const Eigen::MatrixXd& psd = table_psd.psd;
    Outputs outputs(s);
    outputs.Text(s.out, SpectrumCsvText({"PSD from the one-third-octave band RMS table " + s.spectrum_file +
                                             " (constant in each band, " + ToString(series) + " edges)"},
                                        table.unit.value_or(""), Quantity(s.asd), f_out, psd, table.channel_names),
                 "the output CSV (-o)");
    if (const auto place = PlacePlot(s, s.out, true))
      outputs.Plot(*place, report::SpectrumTablePlot(
                               f_out, psd, table.channel_names, table.unit.value_or(""), s.asd,
                               std::string(s.asd ? "ASD" : "PSD") + " from the band RMS table " +
                                   SourceName(s.spectrum_file) + " (constant in each band)",
                               place->stem));
    outputs.Write();
    PrintWritten(outputs, s.out);
    return 0;
  }
  const SpectrumCsv csv = ReadSpectrumCsv(s.spectrum_file);
  const std::string from = csv.unit.value_or(s.unit);
  std::string to = s.to_unit.empty() ? from : s.to_unit;
  Eigen::MatrixXd psd = csv.psd;
  Eigen::MatrixXd bounds = csv.bounds;  // confidence bounds convert with their channels
  std::vector<std::string> comments = {"converted from " + s.spectrum_file};
  if (csv.interpolation == SpectrumInterpolation::kBins) comments.push_back("interpolation: bins");
  if (!s.to_unit.empty()) {
    if (from.empty())
      throw InputError(s.spectrum_file + ": --to needs the spectrum's unit: give '# unit:' in the file or --unit");
    const UnitConversion conv = ConvertUnit(from, to);
    for (std::size_t k = 0; k < csv.f_hz.size(); ++k) {
      psd.row(static_cast<Eigen::Index>(k)) *= conv.PsdFactor(csv.f_hz[k]);
      if (bounds.cols() > 0) bounds.row(static_cast<Eigen::Index>(k)) *= conv.PsdFactor(csv.f_hz[k]);
    }
    comments.push_back(from + " -> " + to + ": " + conv.Describe());
  }
  Outputs outputs(s);
  if (s.asd) bounds = bounds.cwiseSqrt();  // extra columns are written as they are
  outputs.Text(s.out,
               SpectrumCsvText(comments, to, Quantity(s.asd), csv.f_hz, psd, csv.channel_names,
                               bounds.cols() > 0 ? &bounds : nullptr, csv.bound_names),
               "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true)) {
    std::string title = std::string(s.asd ? "ASD" : "PSD") + " of " + SourceName(s.spectrum_file);
    if (!s.to_unit.empty()) title += ", converted from " + report::UnitText(from) + " to " + report::UnitText(to);
    outputs.Plot(*place, report::SpectrumTablePlot(csv.f_hz, psd, csv.channel_names, to, s.asd, title, place->stem));
  }
  outputs.Write();
  PrintWritten(outputs, s.out);
  return 0;
}

int RunReference(const Settings& s) {
  const PetersonModel model = ParsePetersonModel(s.model);
  const std::string unit = s.to_unit.empty() ? PetersonSpectrum::kUnit : s.to_unit;
  const UnitConversion conv = ConvertUnit(PetersonSpectrum::kUnit, unit);
  if (!(s.points_per_decade >= 1.0 && s.points_per_decade <= limits::kMaxPointsPerDecade))
    throw InputError("--points-per-decade " + NumberText(s.points_per_decade) + " is invalid; it must be from 1 to " +
                     std::to_string(static_cast<long long>(limits::kMaxPointsPerDecade)));
  const std::vector<double> f = PetersonFrequencies(s.points_per_decade);
  Eigen::MatrixXd psd(static_cast<Eigen::Index>(f.size()), 1);
  for (std::size_t k = 0; k < f.size(); ++k)
    psd(static_cast<Eigen::Index>(k), 0) = PetersonAccelerationPsd(model, f[k]) * conv.PsdFactor(f[k]);
  Outputs outputs(s);
  outputs.Text(s.out, SpectrumCsvText({"Peterson (1993), USGS OFR 93-322, " + ToString(model) +
                                           ": vertical ground motion, converted from m/s^2: " + conv.Describe()},
                                      unit, Quantity(s.asd), f, psd, {ToString(model)}),
               "the output CSV (-o)");
  if (const auto place = PlacePlot(s, s.out, true))
    outputs.Plot(*place, report::PetersonPlot(model, f, unit, s.asd, place->stem));
  outputs.Write();
  PrintWritten(outputs, s.out);
  return 0;
}

}  // namespace deb::tools
