#include "deb/spectra/spectrum_csv.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>

#include "deb/core/error.h"
#include "deb/spectra/number_text.h"

namespace deb {
namespace {

struct Cell {
  std::string text;
  int column = 1;  // 1-based character position of the cell in its line
};

bool IsSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

std::string Trim(const std::string& text) {
  std::size_t begin = 0, end = text.size();
  while (begin < end && IsSpace(text[begin])) ++begin;
  while (end > begin && IsSpace(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// Splits on commas when the line has one, else on runs of whitespace.
std::vector<Cell> SplitCells(const std::string& line) {
  std::vector<Cell> cells;
  if (line.find(',') != std::string::npos) {
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = line.find(',', start);
      const std::string raw = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      std::size_t lead = 0;
      while (lead < raw.size() && IsSpace(raw[lead])) ++lead;
      cells.push_back({Trim(raw), static_cast<int>(start + lead) + 1});
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  } else {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && IsSpace(line[i])) ++i;
      if (i == line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !IsSpace(line[i])) ++i;
      cells.push_back({line.substr(start, i - start), static_cast<int>(start) + 1});
    }
  }
  return cells;
}

enum class NumberStatus { kOk, kNotANumber, kNotFinite, kOutOfRange };

NumberStatus ParseNumber(const std::string& text, double* value) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (begin != end && *begin == '+') ++begin;  // from_chars rejects a leading '+'
  if (begin == end) return NumberStatus::kNotANumber;
  const auto result = std::from_chars(begin, end, *value);
  if (result.ptr != end) return NumberStatus::kNotANumber;
  if (result.ec == std::errc::result_out_of_range) return NumberStatus::kOutOfRange;
  if (result.ec != std::errc()) return NumberStatus::kNotANumber;
  if (!std::isfinite(*value)) return NumberStatus::kNotFinite;
  return NumberStatus::kOk;
}

class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) { csv_.path = name_; }

  [[noreturn]] void Fail(int line, int column, const std::string& message) const {
    throw InputError(name_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message);
  }

  // "# key: value" with a known key sets metadata; anything else is a comment.
  void Comment(const std::string& line, std::size_t hash, int line_no) {
    const std::string body = line.substr(hash + 1);
    const std::size_t colon = body.find(':');
    if (colon == std::string::npos) return;
    const std::string key = Lower(Trim(body.substr(0, colon)));
    if (key != "unit" && key != "quantity" && key != "sides") return;
    const std::string value = Trim(body.substr(colon + 1));
    std::size_t lead = colon + 1;
    while (lead < body.size() && IsSpace(body[lead])) ++lead;
    const int column = static_cast<int>(hash + 1 + lead) + 1;
    if (!seen_keys_.insert(key).second) {
      Fail(line_no, column, "'# " + key + ":' is given twice; give it once");
    }
    if (key == "unit") {
      if (value.empty()) Fail(line_no, column, "'# unit:' has no value");
      csv_.unit = value;
      return;
    }
    try {
      if (key == "quantity") {
        csv_.quantity = ParseSpectrumQuantity(Lower(value));
      } else {
        csv_.sides = ParseSpectrumSides(Lower(value));
      }
    } catch (const InputError& error) {
      Fail(line_no, column, error.what());
    }
  }

  void Row(const std::vector<Cell>& cells, int line_no, const std::string& line) {
    const bool first = columns_ == 0;
    double probe = 0.0;
    if (first && ParseNumber(cells.front().text, &probe) == NumberStatus::kNotANumber) {
      Header(cells, line_no);
      return;
    }
    if (first) {
      Columns(cells, line_no);
      for (std::size_t c = 1; c < cells.size(); ++c) csv_.channel_names.push_back("ch" + std::to_string(c));
    }
    if (cells.size() != columns_) {
      const int column = cells.size() > columns_ ? cells[columns_].column : static_cast<int>(line.size()) + 1;
      Fail(line_no, column,
           "row has " + std::to_string(cells.size()) + " cells; expected " + std::to_string(columns_) +
               " as on line " + std::to_string(columns_line_));
    }
    std::vector<double> values(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) values[c] = Number(cells[c], line_no, c);
    if (values[0] <= 0.0) {
      Fail(line_no, cells[0].column, "frequency " + cells[0].text + " Hz is not > 0");
    }
    if (!f_hz_.empty() && !(values[0] > f_hz_.back())) {
      Fail(line_no, cells[0].column,
           "frequency " + cells[0].text + " Hz is not greater than " + NumberText(f_hz_.back()) +
               " Hz on line " + std::to_string(last_row_line_) + "; frequencies must increase strictly");
    }
    for (std::size_t c = 1; c < cells.size(); ++c) {
      if (values[c] < 0.0) {
        Fail(line_no, cells[c].column,
             ToString(csv_.quantity) + " '" + cells[c].text + "' in column '" + csv_.channel_names[c - 1] +
                 "' is negative; values must be >= 0");
      }
    }
    f_hz_.push_back(values[0]);
    rows_.push_back(std::move(values));
    last_row_line_ = line_no;
  }

  SpectrumCsv Finish() {
    if (rows_.size() < 2) {
      throw InputError(name_ + ": " + std::to_string(rows_.size()) +
                       " data rows; a spectrum needs at least 2 (frequency, value) rows");
    }
    // Convert once: ASD -> PSD by squaring, two-sided -> one-sided by x2.
    const double sides_factor = csv_.sides == SpectrumSides::kTwo ? 2.0 : 1.0;
    csv_.f_hz = f_hz_;
    csv_.psd.resize(static_cast<Eigen::Index>(rows_.size()), static_cast<Eigen::Index>(columns_ - 1));
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      for (std::size_t c = 1; c < columns_; ++c) {
        const double v = rows_[i][c];
        const double psd = csv_.quantity == SpectrumQuantity::kAsd ? v * v : v;
        csv_.psd(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c - 1)) = sides_factor * psd;
      }
    }
    return std::move(csv_);
  }

 private:
  void Columns(const std::vector<Cell>& cells, int line_no) {
    if (cells.size() < 2) {
      Fail(line_no, cells.front().column,
           "row has 1 cell; a spectrum row needs a frequency and at least one channel");
    }
    columns_ = cells.size();
    columns_line_ = line_no;
  }

  void Header(const std::vector<Cell>& cells, int line_no) {
    Columns(cells, line_no);
    for (std::size_t c = 1; c < cells.size(); ++c) {
      if (cells[c].text.empty()) Fail(line_no, cells[c].column, "empty column name");
      csv_.channel_names.push_back(cells[c].text);
    }
  }

  double Number(const Cell& cell, int line_no, std::size_t c) const {
    const std::string what = c == 0 ? "frequency" : "column '" + csv_.channel_names[c - 1] + "'";
    double value = 0.0;
    switch (ParseNumber(cell.text, &value)) {
      case NumberStatus::kOk: return value;
      case NumberStatus::kNotANumber:
        Fail(line_no, cell.column,
             cell.text.empty() ? what + ": empty cell; every cell needs a number"
                               : what + ": '" + cell.text + "' is not a number");
      case NumberStatus::kNotFinite:
        Fail(line_no, cell.column, what + ": '" + cell.text + "' is not finite; values must be finite");
      case NumberStatus::kOutOfRange:
        Fail(line_no, cell.column, what + ": '" + cell.text + "' is outside the range of a double");
    }
    return value;
  }

  std::string name_;
  SpectrumCsv csv_;
  std::set<std::string> seen_keys_;
  std::size_t columns_ = 0;
  int columns_line_ = 0;
  int last_row_line_ = 0;
  std::vector<double> f_hz_;
  std::vector<std::vector<double>> rows_;
};

}  // namespace

std::string ToString(SpectrumQuantity quantity) { return quantity == SpectrumQuantity::kPsd ? "psd" : "asd"; }

std::string ToString(SpectrumSides sides) { return sides == SpectrumSides::kOne ? "one" : "two"; }

SpectrumQuantity ParseSpectrumQuantity(const std::string& text) {
  if (text == "psd") return SpectrumQuantity::kPsd;
  if (text == "asd") return SpectrumQuantity::kAsd;
  throw InputError("unknown spectrum quantity '" + text + "'; allowed: psd, asd");
}

SpectrumSides ParseSpectrumSides(const std::string& text) {
  if (text == "one") return SpectrumSides::kOne;
  if (text == "two") return SpectrumSides::kTwo;
  throw InputError("unknown spectrum sides '" + text + "'; allowed: one, two");
}

SpectrumCsv ParseSpectrumCsv(std::istream& in, const std::string& name) {
  Reader reader(name);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) {
      if (Trim(line.substr(0, hash)).empty()) {
        reader.Comment(line, hash, line_no);
        continue;
      }
      line.erase(hash);  // trailing comment after data
    }
    if (Trim(line).empty()) continue;
    reader.Row(SplitCells(line), line_no, line);
  }
  return reader.Finish();
}

SpectrumCsv ReadSpectrumCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw InputError(path + ": cannot open spectrum file (" + std::strerror(errno) + ")");
  }
  return ParseSpectrumCsv(in, path);
}

std::shared_ptr<const MeasuredSpectrum> MakeMeasuredSpectrum(const SpectrumCsv& csv, Extrapolation extrapolation) {
  MeasuredSpectrumOptions options;
  options.extrapolation = extrapolation;
  options.channel_names = csv.channel_names;
  options.unit = csv.unit.value_or("");
  options.origin = csv.path;
  return std::make_shared<MeasuredSpectrum>(csv.f_hz, csv.psd, options);
}

}  // namespace deb
