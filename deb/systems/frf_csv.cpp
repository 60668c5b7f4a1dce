#include "deb/systems/frf_csv.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/number_text.h"
#include "deb/core/numeric_table.h"
#include "deb/core/suggest.h"

namespace deb {
namespace {

enum class Part { kRe, kIm, kMag, kDb, kPhaseDeg, kCoherence };  // coherence: skipped

// The two columns of one entry, by part.
using Entry = std::map<Part, std::size_t>;

std::string Join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

int IndexIn(std::vector<std::string>& names, const std::string& name, bool fixed) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<int>(it - names.begin());
  if (fixed) return -1;
  names.push_back(name);
  return static_cast<int>(names.size()) - 1;
}

FrfCsv FromTable(const NumericTable& t, std::vector<std::string> outputs, std::vector<std::string> inputs,
                 Extrapolation extrapolation) {
  if (t.header.empty()) {
    const int line = t.rows.empty() ? 1 : t.rows.front().line;
    t.Fail(line, 1,
           "a frequency response file needs a header row: the frequency column, then OUTPUT/INPUT.PART per column "
           "(parts re, im | mag, phase_deg | db, phase_deg)");
  }
  const bool fixed_out = !outputs.empty(), fixed_in = !inputs.empty();
  std::map<std::pair<int, int>, Entry> entries;
  const std::map<std::string, Part> parts = {
      {"re", Part::kRe}, {"im", Part::kIm}, {"mag", Part::kMag}, {"db", Part::kDb}, {"phase_deg", Part::kPhaseDeg},
      {"coherence", Part::kCoherence}};
  for (std::size_t c = 1; c < t.header.size(); ++c) {
    const std::string& name = t.header[c];
    const int line = t.header_line, col = t.header_columns[c];
    const std::size_t slash = name.find('/'), dot = name.rfind('.');
    if (slash == std::string::npos || dot == std::string::npos || dot < slash || slash == 0 || dot == slash + 1)
      t.Fail(line, col, "column '" + name + "' is not named OUTPUT/INPUT.PART (e.g. z/F.re)");
    const auto part = parts.find(name.substr(dot + 1));
    if (part == parts.end())
      t.Fail(line, col, "column '" + name + "': unknown part '" + name.substr(dot + 1) +
                            "'; allowed: re, im, mag, db, phase_deg (and coherence, skipped)");
    if (part->second == Part::kCoherence) continue;
    const std::string out = name.substr(0, slash), in = name.substr(slash + 1, dot - slash - 1);
    const int o = IndexIn(outputs, out, fixed_out), i = IndexIn(inputs, in, fixed_in);
    if (o < 0)
      t.Fail(line, col, "column '" + name + "': output '" + out + "'" + DidYouMean(out, outputs) +
                            " is not one of the path's outputs (" + Join(outputs) + ")");
    if (i < 0)
      t.Fail(line, col, "column '" + name + "': input '" + in + "'" + DidYouMean(in, inputs) +
                            " is not one of the path's inputs (" + Join(inputs) + ")");
    Entry& e = entries[{o, i}];
    if (e.count(part->second)) t.Fail(line, col, "column '" + name + "' is given twice");
    e[part->second] = c;
  }
  for (int o = 0; o < static_cast<int>(outputs.size()); ++o)
    for (int i = 0; i < static_cast<int>(inputs.size()); ++i) {
      const std::string stem = outputs[o] + "/" + inputs[i];
      const auto it = entries.find({o, i});
      const Entry cols = it == entries.end() ? Entry{} : it->second;
      const bool re_im = cols.size() == 2 && cols.count(Part::kRe) && cols.count(Part::kIm);
      const bool polar = cols.size() == 2 && cols.count(Part::kPhaseDeg) && (cols.count(Part::kMag) || cols.count(Part::kDb));
      if (!re_im && !polar)
        t.Fail(t.header_line, 1,
               "entry " + stem + " needs two columns: " + stem + ".re and " + stem + ".im, or " + stem + ".mag (or " +
                   stem + ".db) and " + stem + ".phase_deg");
    }

  std::vector<double> f_hz;
  std::vector<Eigen::MatrixXcd> h;
  int last_line = 0;
  for (const NumericTable::Row& row : t.rows) {
    const double f = row.values[0];
    if (f <= 0.0) t.Fail(row.line, row.columns[0], "frequency " + NumberText(f) + " Hz is not > 0");
    if (!f_hz.empty() && !(f > f_hz.back()))
      t.Fail(row.line, row.columns[0],
             "frequency " + NumberText(f) + " Hz is not greater than " + NumberText(f_hz.back()) + " Hz on line " +
                 std::to_string(last_line) + "; frequencies must increase strictly");
    Eigen::MatrixXcd m(static_cast<Eigen::Index>(outputs.size()), static_cast<Eigen::Index>(inputs.size()));
    for (const auto& entry : entries) {
      const auto& e = entry.second;
      const auto v = [&](Part p) { return row.values[e.at(p)]; };
      std::complex<double> value;
      if (e.count(Part::kRe)) {
        value = {v(Part::kRe), v(Part::kIm)};
      } else {
        double mag = 0.0;
        if (e.count(Part::kMag)) {
          mag = v(Part::kMag);
          if (mag < 0.0)
            t.Fail(row.line, row.columns[e.at(Part::kMag)],
                   "column '" + t.header[e.at(Part::kMag)] + "': a magnitude must be >= 0");
        } else {
          mag = std::pow(10.0, v(Part::kDb) / 20.0);
        }
        value = std::polar(mag, v(Part::kPhaseDeg) * kPi / 180.0);
      }
      m(entry.first.first, entry.first.second) = value;
    }
    f_hz.push_back(f);
    h.push_back(std::move(m));
    last_line = row.line;
  }
  if (t.rows.size() < 2)
    throw InputError(t.name + ": " + std::to_string(t.rows.size()) +
                     " data rows; a frequency response needs at least 2");
  return {outputs, inputs, MeasuredResponse(std::move(f_hz), std::move(h), extrapolation, t.name)};
}

NumericTableOptions FrfTableOptions() {
  NumericTableOptions options;
  options.first_column = "frequency";
  return options;
}

}  // namespace

std::string FrfCsvText(const std::vector<std::string>& comments, const std::vector<double>& f_hz,
                       const std::string& input, const std::vector<std::string>& outputs, const Eigen::MatrixXcd& h,
                       const Eigen::MatrixXd& coherence) {
  const auto rows = static_cast<Eigen::Index>(f_hz.size()), cols = static_cast<Eigen::Index>(outputs.size());
  DEB_DEMAND(h.rows() == rows && h.cols() == cols);
  const bool with_coherence = coherence.size() > 0;
  DEB_DEMAND(!with_coherence || (coherence.rows() == rows && coherence.cols() == cols));
  std::string text;
  for (const std::string& c : comments) text += "# " + c + "\n";
  text += "f_hz";
  for (const std::string& o : outputs) {
    const std::string stem = o + "/" + input;
    text += ", " + stem + ".mag, " + stem + ".phase_deg";
    if (with_coherence) text += ", " + stem + ".coherence";
  }
  text += "\n";
  for (Eigen::Index k = 0; k < rows; ++k) {
    if (!(f_hz[static_cast<std::size_t>(k)] > 0.0)) continue;
    text += NumberText(f_hz[static_cast<std::size_t>(k)]);
    for (Eigen::Index o = 0; o < cols; ++o) {
      text += ", " + NumberText(std::abs(h(k, o))) + ", " + NumberText(std::arg(h(k, o)) * 180.0 / kPi);
      if (with_coherence) text += ", " + NumberText(coherence(k, o));
    }
    text += "\n";
  }
  return text;
}

FrfCsv ReadFrfCsv(const std::string& path, const std::vector<std::string>& outputs,
                  const std::vector<std::string>& inputs, Extrapolation extrapolation) {
  return FromTable(ReadNumericTable(path, FrfTableOptions(), "frequency response file"), outputs, inputs,
                   extrapolation);
}

FrfCsv ParseFrfCsv(std::istream& in, const std::string& name, const std::vector<std::string>& outputs,
                   const std::vector<std::string>& inputs, Extrapolation extrapolation) {
  return FromTable(ParseNumericTable(in, name, FrfTableOptions()), outputs, inputs, extrapolation);
}

}  // namespace deb
