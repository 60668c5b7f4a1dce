#include "deb/spectra/band_table.h"

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/core/numeric_table.h"

namespace deb {
namespace {

struct Cell {
  std::size_t begin = 0, end = 0;  // [begin, end) in the line, trimmed
};

// The cells of a data line: split at commas, or at whitespace when it has none.
std::vector<Cell> Cells(const std::string& line) {
  std::vector<Cell> cells;
  const std::size_t hash = line.find('#');
  const std::size_t n = hash == std::string::npos ? line.size() : hash;
  const bool commas = line.find(',') < n;
  std::size_t i = 0;
  while (i <= n) {
    std::size_t j = i;
    if (commas) {
      while (j < n && line[j] != ',') ++j;
    } else {
      while (i < n && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      if (i >= n) break;
      j = i;
      while (j < n && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    }
    Cell c{i, j};
    while (c.begin < c.end && std::isspace(static_cast<unsigned char>(line[c.begin]))) ++c.begin;
    while (c.end > c.begin && std::isspace(static_cast<unsigned char>(line[c.end - 1]))) --c.end;
    cells.push_back(c);
    i = j + 1;
  }
  return cells;
}

bool IsComment(const std::string& line) {
  const std::size_t first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

}  // namespace

bool IsBandTableExtraColumn(const std::string& name) {
  return name == "lo_hz" || name == "hi_hz" || name == "points" ||
         (name.size() > 6 && name.compare(name.size() - 6, 6, "_class") == 0);
}

BandTable ParseBandTable(const std::string& text, const std::string& name) {
  // The extra columns' cells (words such as VC-D) become a 0 of the same
  // width, so that the numeric reader keeps every other cell's position.
  std::istringstream in(text);
  std::ostringstream numeric;
  std::string line;
  std::vector<bool> extra;
  bool header_seen = false;
  while (std::getline(in, line)) {
    if (!IsComment(line)) {
      const std::vector<Cell> cells = Cells(line);
      if (!header_seen) {
        header_seen = true;
        const std::string first = cells.empty() ? "" : line.substr(cells[0].begin, cells[0].end - cells[0].begin);
        char* end = nullptr;
        std::strtod(first.c_str(), &end);
        if (!first.empty() && end && *end != '\0')  // a header row
          for (const Cell& c : cells) extra.push_back(IsBandTableExtraColumn(line.substr(c.begin, c.end - c.begin)));
      } else {
        for (std::size_t k = 0; k < cells.size() && k < extra.size(); ++k)
          if (extra[k] && cells[k].end > cells[k].begin) {
            line[cells[k].begin] = '0';
            for (std::size_t p = cells[k].begin + 1; p < cells[k].end; ++p) line[p] = ' ';
          }
      }
    }
    numeric << line << '\n';
  }
  NumericTableOptions options;
  options.metadata_keys = {"unit", "quantity", "sides"};
  options.first_column = "centre frequency";
  options.unnamed_prefix = "ch";
  std::istringstream numeric_in(numeric.str());
  const NumericTable table = ParseNumericTable(numeric_in, name, options);
  for (const char* key : {"quantity", "sides"}) {
    const auto it = table.metadata.find(key);
    if (it != table.metadata.end())
      table.Fail(it->second.line, it->second.column,
                 std::string("a band table holds band RMS values, which have no '# ") + key + ":'; remove the line");
  }
  BandTable out;
  out.path = name;
  if (const auto it = table.metadata.find("unit"); it != table.metadata.end()) out.unit = it->second.value;
  std::vector<std::size_t> channels;
  for (std::size_t c = 1; c < table.columns(); ++c)
    if (!(c < extra.size() && extra[c])) {
      channels.push_back(c);
      out.channel_names.push_back(table.ColumnName(c));
    }
  if (table.rows.empty()) throw InputError(name + ": no bands; a band table needs at least one row");
  if (channels.empty()) {
    const int line_no = table.header_line ? table.header_line : table.rows.front().line;
    table.Fail(line_no, 1, "no channel column: a band table needs centre_hz and at least one band-RMS column");
  }
  out.rms.resize(static_cast<Eigen::Index>(table.rows.size()), static_cast<Eigen::Index>(channels.size()));
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const NumericTable::Row& row = table.rows[i];
    const double f = row.values[0];
    if (f <= 0.0) table.Fail(row.line, row.columns[0], "centre frequency " + NumberText(f) + " Hz is not > 0");
    if (!out.centre_hz.empty() && !(f > out.centre_hz.back()))
      table.Fail(row.line, row.columns[0],
                 "centre frequency " + NumberText(f) + " Hz is not greater than the one before; bands must ascend");
    out.centre_hz.push_back(f);
    for (std::size_t k = 0; k < channels.size(); ++k) {
      const double v = row.values[channels[k]];
      if (v < 0.0)
        table.Fail(row.line, row.columns[channels[k]],
                   "band RMS '" + NumberText(v) + "' in column '" + out.channel_names[k] + "' is negative");
      out.rms(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = v;
    }
  }
  return out;
}

BandTable ReadBandTable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the band table");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseBandTable(text.str(), path);
}

namespace {

// 10 significant digits.
std::string Number(double v) { return SignificantText(v, 10); }

}  // namespace

std::string BandTableText(const std::vector<std::string>& comments, const std::string& unit,
                          const std::vector<std::string>& channel_names, const SpectrumClasses& classes) {
  const std::vector<std::vector<BandRms>>& per_channel = classes.bands;
  const bool classified = !classes.classes.empty();
  DEB_DEMAND(!per_channel.empty() && per_channel.size() == channel_names.size());
  std::ostringstream out;
  for (const std::string& c : comments) out << "# " << c << "\n";
  if (!unit.empty()) out << "# unit: " << unit << "\n";  // for convert --from-bands
  out << "centre_hz, lo_hz, hi_hz, points";
  for (const std::string& n : channel_names) out << ", " << n << (classified ? ", " + n + "_class" : "");
  out << "\n";
  for (std::size_t i = 0; i < per_channel.front().size(); ++i) {
    const BandRms& b = per_channel.front()[i];
    out << Number(b.band.centre_hz) << ", " << Number(b.band.lo_hz) << ", " << Number(b.band.hi_hz) << ", " << b.points;
    for (std::size_t c = 0; c < per_channel.size(); ++c) {
      out << ", " << Number(per_channel[c][i].rms);
      if (classified) {
        const BandVerdict& v = classes.classes[c].bands[i];
        out << ", " << (!v.assessed ? "-" : v.best ? classes.classes[c].criteria[*v.best].name : "none");
      }
    }
    out << "\n";
  }
  return out.str();
}

BandTablePsd PsdOfBandTable(const BandTable& table, ThirdOctaveSeries series) {
  std::vector<ThirdOctaveBand> bands;
  for (double f : table.centre_hz) bands.push_back(ThirdOctaveBandNear(f, series));
  BandTablePsd out;
  for (Eigen::Index c = 0; c < table.rms.cols(); ++c) {
    const Eigen::VectorXd col = table.rms.col(c);
    const PsdTable t = BandRmsToPsd(bands, std::vector<double>(col.data(), col.data() + col.size()));
    if (c == 0) {
      out.f_hz = t.f_hz;
      out.psd.resize(static_cast<Eigen::Index>(t.f_hz.size()), table.rms.cols());
    }
    out.psd.col(c) = Eigen::Map<const Eigen::VectorXd>(t.psd.data(), static_cast<Eigen::Index>(t.psd.size()));
  }
  return out;
}

}  // namespace deb
