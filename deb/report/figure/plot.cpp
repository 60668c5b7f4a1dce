#include "deb/report/figure/plot.h"

#include <charconv>

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <set>

#include "deb/core/file_name.h"
#include "deb/core/number_text.h"
#include "deb/units/unit.h"

namespace deb::report {
namespace {

bool IsLetter(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }

// "um" -> "µm" where the rest of a letter run is a unit symbol; "sqrt(Hz)" -> "√Hz".
std::string Micro(const std::string& unit) {
  static const std::set<std::string> kSymbols = {"m", "s", "rad", "g", "N", "V", "A", "Pa", "Hz", "W", "J", "K", "l", "L"};
  std::string s = DisplayUnit(unit), out;
  for (std::size_t i = 0; i < s.size();) {
    if (IsLetter(s[i])) {
      std::size_t j = i;
      while (j < s.size() && IsLetter(s[j])) ++j;
      const std::string word = s.substr(i, j - i);
      if (word.size() > 1 && word[0] == 'u' && kSymbols.count(word.substr(1))) out += "µ" + word.substr(1);
      else if (word == "sqrt" && s.compare(j, 4, "(Hz)") == 0) {
        out += "√Hz";
        j += 4;
      } else
        out += word;
      i = j;
    } else {
      out += s[i++];
    }
  }
  return out;
}

}  // namespace

std::string Quote(const std::string& text) {
  std::string q = "'";
  for (char c : text) {
    if (c == '\'') q += "''";
    else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) q += ' ';  // a line break would end the command
    else q += c;
  }
  return q + "'";
}

std::string QuoteFile(const std::string& path) {
  const bool pipe_like = !path.empty() && (path[0] == '|' || path[0] == '<' || path[0] == '!');
  return Quote(pipe_like ? "./" + path : path);
}

std::string DrawCommands(const std::string& terminal, const std::string& output_file, const std::string& script_file) {
  return terminal + "set output " + QuoteFile(output_file) + "\nload " + QuoteFile(script_file) + "\nunset output\n";
}

std::string QuoteLines(const std::vector<std::string>& lines) {
  if (lines.empty()) return Quote("");
  std::string q = "(";
  for (std::size_t i = 0; i < lines.size(); ++i) q += (i ? ".\"\\n\"." : "") + Quote(lines[i]);
  return q + ")";
}

std::string QuoteLines(const std::string& text) {
  std::vector<std::string> lines(1);
  for (char c : text) {
    if (c == '\n') lines.emplace_back();
    else lines.back() += c;
  }
  return QuoteLines(lines);
}

std::string Enhanced(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '_' || c == '^' || c == '@' || c == '&' || c == '~' || c == '{' || c == '}' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

std::string UnitLabel(const std::string& unit) {
  const std::string s = Micro(unit);
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '^') {
      std::size_t j = i + 1;
      if (j < s.size() && (s[j] == '-' || s[j] == '+')) ++j;
      while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
      out += "^{" + s.substr(i + 1, j - i - 1) + "}";
      i = j - 1;
    } else {
      out += Enhanced(std::string(1, s[i]));
    }
  }
  return out;
}

std::string UnitText(const std::string& unit) { return Micro(unit); }

std::string VarianceUnit(const std::string& unit) {
  const std::string psd = PsdUnitLabel(unit);  // "...^2/Hz" or "1/Hz"
  const std::string variance = psd.substr(0, psd.size() - 3);
  return variance.empty() ? "1" : variance;
}

std::string Sig(double value, int digits) {
  char text[64];
  if (value == 0.0 || !std::isfinite(value)) {
    std::snprintf(text, sizeof(text), "%g", value);
    return text;
  }
  const double mag = std::fabs(value);
  if (mag >= 1e-3 && mag < 1e5) {
    const int exponent = static_cast<int>(std::floor(std::log10(mag)));
    int decimals = std::max(0, digits - 1 - exponent);
    std::snprintf(text, sizeof(text), "%.*f", decimals, value);
    // Rounding may carry into a new digit (9.996 -> "10.00"): drop one decimal.
    std::string s = text;
    if (decimals > 0 && std::fabs(std::stod(s)) >= std::pow(10.0, exponent + 1)) {
      std::snprintf(text, sizeof(text), "%.*f", decimals - 1, value);
      s = text;
    }
    return s;
  }
  std::snprintf(text, sizeof(text), "%.*e", digits - 1, value);
  return text;
}

std::string SigLabel(double value, int digits) {
  const std::string s = Sig(value, digits);
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  const int exponent = std::stoi(s.substr(e + 1));
  return s.substr(0, e) + "·10^{" + std::to_string(exponent) + "}";
}

std::string Short(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

namespace {

// The exponent of a frequency that is a power of ten from 10^4 up or 10^-4
// down (HzLabel, HzText); none for anything else.
std::optional<int> LargePowerOfTen(double f_hz) {
  const double e = std::round(std::log10(f_hz));
  if (std::fabs(e) >= 4 && std::fabs(f_hz / std::pow(10.0, e) - 1.0) < 1e-9) return static_cast<int>(e);
  return std::nullopt;
}

}  // namespace

std::string HzLabel(double f_hz) {
  if (const std::optional<int> e = LargePowerOfTen(f_hz)) return "10^{" + std::to_string(*e) + "}";
  return Short(f_hz);
}

std::string HzText(double f_hz) {
  if (const std::optional<int> e = LargePowerOfTen(f_hz)) return "10" + SuperscriptText(std::to_string(*e));
  return Short(f_hz);
}

std::string Squared(std::string unit) {
  for (std::size_t at = unit.find("^2"); at != std::string::npos; at = unit.find("^2", at)) unit.replace(at, 2, "²");
  return unit;
}

std::string Share(double part, double whole) {
  if (!(whole > 0.0)) return "–";
  const double percent = 100.0 * part / whole;
  // Below 0.01 % in size, either sign (a mode's cross term that takes a
  // little away, a variance that fell a little): "< 0.01 %", as compare's
  // headline writes a change that small ("> −0.01 %" read as unclear).
  if (percent != 0.0 && std::abs(percent) < 0.01) return "< 0.01 %";
  return Sig(percent, 3) + " %";
}

std::string FileStem(const std::string& name) {
  const std::string s = name.empty() ? "_" : FileNameWord(name);
  if (s.size() <= 100) return s;
  // FNV-1a of the name: the same on every machine and run.
  std::uint64_t hash = 14695981039346656037ull;
  for (char c : name) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  char tail[20];
  std::snprintf(tail, sizeof tail, "~%016llx", static_cast<unsigned long long>(hash));
  return s.substr(0, 80) + tail;
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string CsvNumber(double value) {
  // std::to_chars with a precision is printf's %.10g, several times faster:
  // plot tables hold 10^5..10^6 numbers.
  char text[32];
  return std::string(text, std::to_chars(text, text + sizeof(text), value, std::chars_format::general, 10).ptr);
}

std::string PlotList(const std::vector<std::string>& clauses) {
  std::string s = "plot ";
  for (std::size_t i = 0; i < clauses.size(); ++i) s += (i ? ", \\\n     " : "") + clauses[i];
  return s + "\n";
}

}  // namespace deb::report
