// Reads tabulated spectra (measured floor vibration, sensor noise curves) from
// a small self-describing text format, and converts them once, at load, to
// deb's convention: one-sided PSD (docs/method.md, conventions 1-2).
//
//   # unit: um/s          unit of the quantity (optional)
//   # quantity: asd       psd (default) or asd: ASD columns are squared
//   # sides: two          one (default) or two: PSD_one = 2 PSD_two
//   # interpolation: bins log-log (default) or bins: constant over each bin
//                         (the bins of a spectral estimate, measured_spectrum.h)
//   f_hz, x, y, z         optional header row: frequency name, channel names
//                         (x_lo, x_hi beside x: x's confidence bounds, not channels)
//   0.5, 1.2e-3, ...      frequency [Hz] first, then one column per channel
//
// Cells are separated by commas or by whitespace; '#' starts a comment (a
// comment line "# key: value" with another key is just a comment). Errors
// quote file:line:column, the offending text and the rule it breaks.
// SpectrumCsvText / WriteSpectrumCsv write the same format.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deb/core/enum_names.h"
#include "deb/spectra/measured_spectrum.h"

namespace deb {

enum class SpectrumQuantity { kPsd, kAsd };
enum class SpectrumSides { kOne, kTwo };

inline constexpr EnumName<SpectrumQuantity> kSpectrumQuantityNames[] = {{SpectrumQuantity::kPsd, "psd"},
                                                                        {SpectrumQuantity::kAsd, "asd"}};
constexpr EnumNames<SpectrumQuantity> NamesOf(SpectrumQuantity) { return kSpectrumQuantityNames; }
inline constexpr EnumName<SpectrumSides> kSpectrumSidesNames[] = {{SpectrumSides::kOne, "one"},
                                                                  {SpectrumSides::kTwo, "two"}};
constexpr EnumNames<SpectrumSides> NamesOf(SpectrumSides) { return kSpectrumSidesNames; }

// @throws InputError naming the text and listing the allowed values.
inline SpectrumQuantity ParseSpectrumQuantity(const std::string& text) {
  return ParseEnum<SpectrumQuantity>(text, "spectrum quantity");
}
inline SpectrumSides ParseSpectrumSides(const std::string& text) {
  return ParseEnum<SpectrumSides>(text, "spectrum sides");
}

struct SpectrumCsv {
  std::string path;                        // as given to the reader
  std::vector<double> f_hz;                // strictly increasing, > 0
  Eigen::MatrixXd psd;                     // one-sided PSD, rows = f_hz, cols = channels
  std::vector<std::string> channel_names;  // from the header row, else "ch1", ...
  // Columns named <channel>_lo / <channel>_hi beside a column <channel>: its
  // confidence bounds (as `deb spectrum welch --bounds` writes them), kept
  // apart from the channels, converted like them; rows = f_hz.
  Eigen::MatrixXd bounds;
  std::vector<std::string> bound_names;
  std::optional<std::string> unit;         // from "# unit:"
  SpectrumQuantity quantity = SpectrumQuantity::kPsd;  // as declared in the file
  bool quantity_declared = false;                      // the file has a "# quantity:" line
  SpectrumSides sides = SpectrumSides::kOne;           // as declared in the file
  SpectrumInterpolation interpolation = SpectrumInterpolation::kLogLog;  // as declared in the file
};

// @throws InputError if the file cannot be read or breaks a rule: a cell that
//   is not a number or not finite, a frequency <= 0 or not greater than the
//   one before, a negative PSD/ASD, a row with a different number of cells, a
//   bad or repeated "# quantity:"/"# sides:"/"# unit:", fewer than 2 rows.
SpectrumCsv ReadSpectrumCsv(const std::string& path);

// Same, from a stream; name stands for the file name in messages.
SpectrumCsv ParseSpectrumCsv(std::istream& in, const std::string& name);

// The table as a spectrum source (independent channels).
std::shared_ptr<const MeasuredSpectrum> MakeMeasuredSpectrum(
    const SpectrumCsv& csv, Extrapolation extrapolation = Extrapolation::kError);

// The text of a spectrum CSV: "# " + each comment, "# unit:" (if any),
// "# quantity:", "# sides: one", the header "f_hz, <names>, <extra_names>",
// then one row per f_hz > 0: the frequency with every digit (band edges 1e-9
// apart stay apart), the one-sided PSD (or its square root for kAsd) and the
// extra columns (rows as f_hz, written as they are) with 10 significant digits.
std::string SpectrumCsvText(const std::vector<std::string>& comments, const std::string& unit,
                            SpectrumQuantity quantity, const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                            const std::vector<std::string>& names, const Eigen::MatrixXd* extra = nullptr,
                            const std::vector<std::string>& extra_names = {});

// SpectrumCsvText written to `path`. @throws WriteError if it cannot be written.
void WriteSpectrumCsv(const std::string& path, const std::vector<std::string>& comments, const std::string& unit,
                      SpectrumQuantity quantity, const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                      const std::vector<std::string>& names);

}  // namespace deb
