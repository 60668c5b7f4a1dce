#include "deb/spectra/spectrum_csv.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/numeric_table.h"
#include "deb/core/output_dir.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// The index in names of the channel whose bound `name` is (<channel>_lo or
// <channel>_hi, the channel itself no bound), or -1.
int BoundOf(const std::string& name, const std::vector<std::string>& names) {
  for (const char* suffix : {"_lo", "_hi"}) {
    if (name.size() <= 3 || name.compare(name.size() - 3, 3, suffix) != 0) continue;
    const std::string channel = name.substr(0, name.size() - 3);
    for (std::size_t c = 0; c < names.size(); ++c)
      if (names[c] == channel && !(channel.size() > 3 && BoundOf(channel, names) >= 0)) return static_cast<int>(c);
  }
  return -1;
}

// The spectrum's rules on a table read by ParseNumericTable: at least a
// frequency and one channel, frequencies > 0 and strictly increasing, values
// >= 0, at least two rows; metadata unit, quantity and sides.
SpectrumCsv FromTable(const NumericTable& table) {
  SpectrumCsv csv;
  csv.path = table.name;
  const auto meta = [&](const char* key, auto parse) {
    const auto it = table.metadata.find(key);
    if (it == table.metadata.end()) return;
    try {
      parse(it->second.value);
    } catch (const InputError& error) {
      table.Fail(it->second.line, it->second.column, error.what());
    }
  };
  meta("unit", [&](const std::string& v) { csv.unit = v; });
  meta("quantity", [&](const std::string& v) {
    csv.quantity = ParseSpectrumQuantity(Lower(v));
    csv.quantity_declared = true;
  });
  meta("sides", [&](const std::string& v) { csv.sides = ParseSpectrumSides(Lower(v)); });
  meta("interpolation", [&](const std::string& v) { csv.interpolation = ParseSpectrumInterpolation(Lower(v)); });

  const std::size_t columns = table.columns();
  if (columns == 1) {
    const int line = table.header_line ? table.header_line : table.rows.front().line;
    const int column = table.header_line ? table.header_columns.front() : table.rows.front().columns.front();
    table.Fail(line, column, "row has 1 cell; a spectrum row needs a frequency and at least one channel");
  }
  // Columns <channel>_lo / <channel>_hi beside a column <channel> are its
  // confidence bounds (deb spectrum welch --bounds), not channels.
  std::vector<std::string> names;
  for (std::size_t c = 1; c < columns; ++c) names.push_back(table.ColumnName(c));
  std::vector<bool> is_bound(names.size(), false);
  for (std::size_t c = 0; c < names.size(); ++c) is_bound[c] = BoundOf(names[c], names) >= 0;
  std::vector<std::size_t> channel_columns, bound_columns;
  for (std::size_t c = 0; c < names.size(); ++c) {
    (is_bound[c] ? bound_columns : channel_columns).push_back(c + 1);
    (is_bound[c] ? csv.bound_names : csv.channel_names).push_back(names[c]);
  }

  int last_line = 0;
  for (const NumericTable::Row& row : table.rows) {
    const double f = row.values[0];
    if (f <= 0.0) table.Fail(row.line, row.columns[0], "frequency " + NumberText(f) + " Hz is not > 0");
    if (!csv.f_hz.empty() && !(f > csv.f_hz.back()))
      table.Fail(row.line, row.columns[0],
                 "frequency " + NumberText(f) + " Hz is not greater than " + NumberText(csv.f_hz.back()) +
                     " Hz on line " + std::to_string(last_line) + "; frequencies must increase strictly");
    for (std::size_t c = 1; c < columns; ++c)
      if (row.values[c] < 0.0)
        table.Fail(row.line, row.columns[c],
                   ToString(csv.quantity) + " '" + NumberText(row.values[c]) + "' in column '" +
                       names[c - 1] + "' is negative; values must be >= 0");
    csv.f_hz.push_back(f);
    last_line = row.line;
  }
  if (table.rows.size() < 2)
    throw InputError(table.name + ": " + std::to_string(table.rows.size()) +
                     " data rows; a spectrum needs at least 2 (frequency, value) rows");

  // Convert once: ASD -> PSD by squaring, two-sided -> one-sided by x2.
  const double sides_factor = csv.sides == SpectrumSides::kTwo ? 2.0 : 1.0;
  const auto fill = [&](Eigen::MatrixXd& m, const std::vector<std::size_t>& cols) {
    m.resize(static_cast<Eigen::Index>(table.rows.size()), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t i = 0; i < table.rows.size(); ++i)
      for (std::size_t k = 0; k < cols.size(); ++k) {
        const double v = table.rows[i].values[cols[k]];
        m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) =
            sides_factor * (csv.quantity == SpectrumQuantity::kAsd ? v * v : v);
      }
  };
  fill(csv.psd, channel_columns);
  fill(csv.bounds, bound_columns);
  return csv;
}

NumericTableOptions SpectrumTableOptions() {
  NumericTableOptions options;
  options.metadata_keys = {"unit", "quantity", "sides", "interpolation"};
  options.first_column = "frequency";
  options.unnamed_prefix = "ch";
  return options;
}

}  // namespace

SpectrumCsv ParseSpectrumCsv(std::istream& in, const std::string& name) {
  return FromTable(ParseNumericTable(in, name, SpectrumTableOptions()));
}

SpectrumCsv ReadSpectrumCsv(const std::string& path) {
  return FromTable(ReadNumericTable(path, SpectrumTableOptions(), "spectrum file"));
}

std::shared_ptr<const MeasuredSpectrum> MakeMeasuredSpectrum(const SpectrumCsv& csv, Extrapolation extrapolation) {
  MeasuredSpectrumOptions options;
  options.extrapolation = extrapolation;
  options.interpolation = csv.interpolation;
  options.channel_names = csv.channel_names;
  options.unit = csv.unit.value_or("");
  options.origin = csv.path;
  return std::make_shared<MeasuredSpectrum>(csv.f_hz, csv.psd, options);
}

std::string SpectrumCsvText(const std::vector<std::string>& comments, const std::string& unit,
                            SpectrumQuantity quantity, const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                            const std::vector<std::string>& names, const Eigen::MatrixXd* extra,
                            const std::vector<std::string>& extra_names) {
  const bool asd = quantity == SpectrumQuantity::kAsd;
  const auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v);
    return std::string(text);
  };
  std::ostringstream out;
  for (const std::string& c : comments) out << "# " << c << "\n";
  if (!unit.empty()) out << "# unit: " << unit << "\n";
  out << "# quantity: " << ToString(quantity) << "\n# sides: one\nf_hz";
  for (const auto& n : names) out << ", " << n;
  for (const auto& n : extra_names) out << ", " << n;
  out << "\n";
  for (std::size_t k = 0; k < f_hz.size(); ++k) {
    if (!(f_hz[k] > 0.0)) continue;
    const auto row = static_cast<Eigen::Index>(k);
    out << NumberText(f_hz[k]);
    for (Eigen::Index c = 0; c < psd.cols(); ++c) out << ", " << number(asd ? std::sqrt(psd(row, c)) : psd(row, c));
    if (extra)
      for (Eigen::Index c = 0; c < extra->cols(); ++c) out << ", " << number((*extra)(row, c));
    out << "\n";
  }
  return out.str();
}

void WriteSpectrumCsv(const std::string& path, const std::vector<std::string>& comments, const std::string& unit,
                      SpectrumQuantity quantity, const std::vector<double>& f_hz, const Eigen::MatrixXd& psd,
                      const std::vector<std::string>& names) {
  WriteTextFile(path, SpectrumCsvText(comments, unit, quantity, f_hz, psd, names));
}

}  // namespace deb
