#include "deb/signal/time_series_file.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

struct Cell {
  const char* begin;
  const char* end;
  int column;  // 1-based
};

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// Commas separate cells when the line has one, else runs of blanks do.
void Split(const std::string& line, std::vector<Cell>* cells) {
  cells->clear();
  const char* p = line.data();
  const char* end = p + line.size();
  if (line.find(',') != std::string::npos) {
    const char* start = p;
    for (const char* q = p;; ++q) {
      if (q == end || *q == ',') {
        const char* b = start;
        const char* e = q;
        while (b < e && IsBlank(*b)) ++b;
        while (e > b && IsBlank(e[-1])) --e;
        cells->push_back({b, e, static_cast<int>(b - p) + 1});
        if (q == end) break;
        start = q + 1;
      }
    }
    return;
  }
  const char* q = p;
  while (q < end) {
    while (q < end && IsBlank(*q)) ++q;
    if (q == end) break;
    const char* b = q;
    while (q < end && !IsBlank(*q)) ++q;
    cells->push_back({b, q, static_cast<int>(b - p) + 1});
  }
}

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string Trim(const std::string& text) {
  std::size_t b = 0, e = text.size();
  while (b < e && std::isspace(static_cast<unsigned char>(text[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(text[e - 1]))) --e;
  return text.substr(b, e - b);
}

// 0: a finite number; 1: not a number; 2: not finite.
int ParseCell(const Cell& cell, double* value) {
  const char* b = cell.begin;
  if (b != cell.end && *b == '+') ++b;
  if (b == cell.end) return 1;
  const auto r = std::from_chars(b, cell.end, *value);
  if (r.ptr != cell.end || (r.ec != std::errc() && r.ec != std::errc::result_out_of_range)) return 1;
  if (r.ec == std::errc::result_out_of_range || !std::isfinite(*value)) return 2;
  return 0;
}

class CsvReader {
 public:
  CsvReader(std::string path, const TimeSeriesCsvOptions& options) : path_(std::move(path)), options_(options) {}

  [[noreturn]] void Fail(int line, int column, const std::string& message) const {
    throw InputError(path_ + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message);
  }

  TimeSeries Read() {
    const std::string text = ReadInputFile(path_, "the time series file", limits::kMaxTextFileBytes);
    TextLines lines(text, path_);
    std::string line;
    std::vector<Cell> cells;
    int line_no = 0;
    while (lines.Next(line)) {
      line_no = lines.line_number();
      const std::size_t hash = line.find('#');
      if (hash != std::string::npos) {
        Comment(line, hash, line_no);
        line.resize(hash);
      }
      Split(line, &cells);
      if (cells.empty()) continue;
      Row(cells, line_no, line);
    }
    return Finish(line_no);
  }

 private:
  void Comment(const std::string& line, std::size_t hash, int line_no) {
    const std::string body = line.substr(hash + 1);
    const std::size_t colon = body.find(':');
    if (colon == std::string::npos) return;
    const std::string key = Lower(Trim(body.substr(0, colon)));
    const std::string value = Trim(body.substr(colon + 1));
    const int column = static_cast<int>(hash) + 2 + static_cast<int>(colon) + 1;
    if (key == "unit") {
      if (value.empty()) Fail(line_no, column, "'# unit:' has no value");
      if (file_unit_) Fail(line_no, column, "'# unit:' is given twice; give it once");
      if (const std::string problem = Utf8Problem(value); !problem.empty()) Fail(line_no, column, "'# unit:' " + problem + "; save the file as UTF-8 text");
      file_unit_ = value;
    } else if (key == "rate_hz") {
      if (file_rate_) Fail(line_no, column, "'# rate_hz:' is given twice; give it once");
      double rate = 0.0;
      const Cell cell{value.data(), value.data() + value.size(), column};
      if (ParseCell(cell, &rate) != 0 || rate <= 0.0)
        Fail(line_no, column, "'# rate_hz: " + value + "' is not a finite sample rate > 0");
      file_rate_ = rate;
    }
  }

  void Row(const std::vector<Cell>& cells, int line_no, const std::string& line) {
    if (columns_ == 0) {
      double probe = 0.0;
      columns_ = cells.size();
      columns_line_ = line_no;
      if (ParseCell(cells.front(), &probe) == 1) {  // a header row
        for (const Cell& c : cells) {
          names_.emplace_back(c.begin, c.end);
          if (const std::string problem = Utf8Problem(names_.back()); !problem.empty())
            Fail(line_no, c.column, "column name '" + Excerpt(names_.back()) + "': " + problem + "; save the file as UTF-8 text");
        }
        const std::string first = Lower(names_.front());
        has_time_ = first == "t" || first == "time" || first == "time_s";
        if (has_time_) names_.erase(names_.begin());
        if (names_.empty()) Fail(line_no, cells.front().column, "a time column alone; at least one channel is needed");
        return;
      }
    }
    if (cells.size() != columns_) {
      const int column = cells.size() > columns_ ? cells[columns_].column : static_cast<int>(line.size()) + 1;
      Fail(line_no, column,
           "row has " + std::to_string(cells.size()) + " cells; expected " + std::to_string(columns_) +
               " as on line " + std::to_string(columns_line_));
    }
    for (std::size_t c = 0; c < cells.size(); ++c) {
      double v = 0.0;
      const int status = ParseCell(cells[c], &v);
      if (status != 0) {
        const std::string text(cells[c].begin, cells[c].end);
        const std::string what = has_time_ && c == 0 ? "time" : "channel '" + ChannelName(c) + "'";
        Fail(line_no, cells[c].column,
             what + ": '" + Excerpt(text) + "' is " + (status == 1 ? "not a number" : "not finite") +
                 "; every sample must be a finite number");
      }
      values_.push_back(v);
    }
    lines_.push_back(line_no);
    columns_of_first_cell_.push_back(cells.front().column);
  }

  std::string ChannelName(std::size_t cell_index) const {
    const std::size_t channel = has_time_ ? cell_index - 1 : cell_index;
    return names_.empty() ? "ch" + std::to_string(channel + 1) : names_[channel];
  }

  TimeSeries Finish(int last_line) {
    const std::size_t rows = lines_.size();
    if (rows == 0) Fail(last_line, 1, "no samples in the file");
    const std::size_t time_cols = has_time_ ? 1 : 0;
    const std::size_t channels = columns_ - time_cols;
    if (channels == 0) Fail(columns_line_, 1, "no channel column");
    double rate = 0.0;
    if (file_rate_ && options_.rate_hz && std::abs(*file_rate_ - *options_.rate_hz) > 1e-6 * *options_.rate_hz)
      throw InputError(path_ + ": the file declares '# rate_hz: " + NumberText(*file_rate_) + "' but " +
                       NumberText(*options_.rate_hz) + " Hz is given; they must agree");
    if (file_rate_) rate = *file_rate_;
    if (options_.rate_hz) rate = *options_.rate_hz;
    if (has_time_) rate = CheckTimeStamps(rate);
    if (rate == 0.0)
      throw InputError(path_ + ": missing sample rate: give '# rate_hz:' in the file, a first column named t, "
                       "time or time_s with time stamps in s, or the rate where the file is used");
    std::string unit = options_.unit;
    if (file_unit_) {
      if (!unit.empty() && unit != *file_unit_)
        throw InputError(path_ + ": the file declares '# unit: " + *file_unit_ + "' but unit '" + unit +
                         "' is given; they must be equal");
      unit = *file_unit_;
    }
    Eigen::MatrixXd samples(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(channels));
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < channels; ++c)
        samples(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = values_[r * columns_ + time_cols + c];
    return TimeSeries(rate, std::move(samples), names_, unit, path_);
  }

  // Rate from the stamps; with a declared rate, the stamps must follow it.
  double CheckTimeStamps(double declared_rate) const {
    const std::size_t rows = lines_.size();
    if (rows < 2) Fail(lines_.front(), 1, "one time stamp; a sample rate needs at least two");
    const double t0 = values_[0];
    const double dt = declared_rate > 0.0 ? 1.0 / declared_rate
                                          : (values_[(rows - 1) * columns_] - t0) / static_cast<double>(rows - 1);
    for (std::size_t r = 1; r < rows; ++r) {
      const double t = values_[r * columns_];
      const double previous = values_[(r - 1) * columns_];
      if (!(t > previous))
        Fail(lines_[r], columns_of_first_cell_[r],
             "time " + NumberText(t) + " s is not greater than " + NumberText(previous) + " s on line " +
                 std::to_string(lines_[r - 1]) + "; time stamps must increase");
    }
    for (std::size_t r = 1; r < rows; ++r) {
      const double t = values_[r * columns_];
      const double expected = t0 + static_cast<double>(r) * dt;
      if (!(std::abs(t - expected) <= 0.01 * dt))
        Fail(lines_[r], columns_of_first_cell_[r],
             "non-uniform time stamps: time " + NumberText(t) + " s is off the uniform grid t0 + i dt = " +
                 NumberText(expected) + " s (dt = " + NumberText(dt) + " s) by more than 1 % of dt; resample the "
                 "recording to a constant rate first");
    }
    return 1.0 / dt;
  }

  std::string path_;
  TimeSeriesCsvOptions options_;
  std::optional<std::string> file_unit_;
  std::optional<double> file_rate_;
  std::vector<std::string> names_;
  bool has_time_ = false;
  std::size_t columns_ = 0;
  int columns_line_ = 0;
  std::vector<double> values_;  // row-major, columns_ per row
  std::vector<int> lines_;
  std::vector<int> columns_of_first_cell_;
};

bool HostIsLittleEndian() {
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

template <typename T>
T LittleEndian(const unsigned char* bytes) {
  unsigned char copy[sizeof(T)];
  std::memcpy(copy, bytes, sizeof(T));
  if (!HostIsLittleEndian()) {
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(copy[i], copy[sizeof(T) - 1 - i]);
  }
  T value;
  std::memcpy(&value, copy, sizeof(T));
  return value;
}

}  // namespace

TimeSeries ReadTimeSeriesCsv(const std::string& path, const TimeSeriesCsvOptions& options) {
  return CsvReader(path, options).Read();
}

TimeSeries ReadRawTimeSeries(const std::string& path, const RawTimeSeriesOptions& options) {
  if (options.rate_hz == 0.0)
    throw InputError(path + ": missing sample rate: a raw file carries none; give it where the file is used");
  if (options.channels < 1)
    throw InputError(path + ": " + std::to_string(options.channels) + " channels; at least 1 is needed");
  const std::string bytes = ReadInputFile(path, "the raw time series file", limits::kMaxRawFileBytes);
  const std::size_t width = options.format == RawSampleFormat::kFloat32 ? 4 : 8;
  const std::size_t frame = width * static_cast<std::size_t>(options.channels);
  if (bytes.empty() || bytes.size() % frame != 0)
    throw InputError(path + ": " + std::to_string(bytes.size()) + " bytes is not a whole number of frames of " +
                     std::to_string(options.channels) + " " + ToString(options.format) + " samples (" +
                     std::to_string(frame) + " bytes each)");
  const std::size_t rows = bytes.size() / frame;
  Eigen::MatrixXd samples(static_cast<Eigen::Index>(rows), options.channels);
  for (std::size_t r = 0; r < rows; ++r) {
    for (int c = 0; c < options.channels; ++c) {
      const unsigned char* p = reinterpret_cast<const unsigned char*>(bytes.data()) + r * frame + static_cast<std::size_t>(c) * width;
      samples(static_cast<Eigen::Index>(r), c) =
          width == 4 ? static_cast<double>(LittleEndian<float>(p)) : LittleEndian<double>(p);
    }
  }
  return TimeSeries(options.rate_hz, std::move(samples), options.channel_names, options.unit, path);
}

}  // namespace deb
