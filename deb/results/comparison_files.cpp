#include "deb/results/comparison_files.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"

namespace deb {
namespace {

using nlohmann::json;

std::string Join(const std::string& where, const std::string& key) { return where.empty() ? key : where + "." + key; }

const json& Member(const json& j, const std::string& key, const std::string& where, const std::string& file) {
  const std::string k = Join(where, key);
  if (!j.is_object() || !j.contains(key))
    throw InputError(k, file + ": " + k + ": missing (is this a summary.json written by deb run?)");
  return j.at(key);
}

double Number(const json& j, const std::string& key, const std::string& where, const std::string& file) {
  const json& v = Member(j, key, where, file);
  const std::string k = Join(where, key);
  if (!v.is_number()) throw InputError(k, file + ": " + k + ": " + Excerpt(v.dump()) + " is not a number");
  return v.get<double>();
}

// A variance: finite and >= 0 (a negative one would give a NaN RMS).
double Variance(const json& j, const std::string& key, const std::string& where, const std::string& file) {
  const double v = Number(j, key, where, file);
  const std::string k = Join(where, key);
  if (!std::isfinite(v) || v < 0.0)
    throw InputError(k, file + ": " + k + ": " + Excerpt(j.at(key).dump()) + " is not a variance (finite, >= 0)");
  return v;
}

const json& List(const json& j, const std::string& key, const std::string& where, const std::string& file) {
  const json& v = Member(j, key, where, file);
  const std::string k = Join(where, key);
  if (!v.is_array())
    throw InputError(k, file + ": " + k + ": " + Excerpt(v.dump()) + " is not a list (is this a summary.json written by deb run?)");
  return v;
}

std::string Text(const json& j, const std::string& key, const std::string& where, const std::string& file) {
  const json& v = Member(j, key, where, file);
  const std::string k = Join(where, key);
  if (!v.is_string()) throw InputError(k, file + ": " + k + ": " + Excerpt(v.dump()) + " is not a string");
  return v.get<std::string>();
}

std::string Index(const std::string& list, std::size_t i) { return list + "[" + std::to_string(i) + "]"; }

json FigureJson(const ComparedFigure& f) {
  return {{"output", f.output},
          {"unit", f.unit},
          {"contributor", f.contributor},
          {"band", f.band.empty() ? json(nullptr) : json(f.band)},
          {"rms_a", f.rms_a},
          {"rms_b", f.rms_b},
          {"difference", f.difference},
          {"ratio", f.ratio ? json(*f.ratio) : json(nullptr)},
          {"variance_change_of_total", f.variance_change_of_total},
          {"negligible_a", f.negligible_a},
          {"negligible_b", f.negligible_b}};
}

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string Num(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace

ResultFigures ReadSummaryFigures(const std::string& file, const std::string& label) {
  const std::string text = ReadInputFile(file, "the summary", limits::kMaxTextFileBytes);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(file + ": not valid JSON: " + e.what());
  }
  ResultFigures r;
  r.label = label;
  // The budget's digest, kept only when it is one (64 hex digits): a
  // document prints it as the input's name.
  if (j.contains("budget_sha256") && j["budget_sha256"].is_string()) {
    const std::string sha = j["budget_sha256"].get<std::string>();
    if (sha.size() == 64 && std::all_of(sha.begin(), sha.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); }))
      r.budget_sha256 = sha;
  }
  const json& outputs = List(j, "outputs", "", file);
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const json& o = outputs[i];
    const std::string where = Index("outputs", i);
    ResultFigures::Output fo;
    fo.name = Text(o, "name", where, file);
    fo.unit = Text(o, "unit", where, file);
    fo.variance = Variance(o, "variance", where, file);
    if (o.contains("requirement") && o["requirement"].is_object())
      fo.rms_max = Number(o["requirement"], "rms_max", where + ".requirement", file);
    if (fo.rms_max && !(std::isfinite(*fo.rms_max) && *fo.rms_max > 0.0))
      throw InputError(where + ".requirement.rms_max", file + ": " + where + ".requirement.rms_max: " +
                                                          Excerpt(o["requirement"]["rms_max"].dump()) +
                                                          " is not a requirement (finite, > 0)");
    const json& cs = List(o, "contributors", where, file);
    for (std::size_t c = 0; c < cs.size(); ++c)
      fo.contributors.push_back({Text(cs[c], "name", where + "." + Index("contributors", c), file),
                                 Variance(cs[c], "variance", where + "." + Index("contributors", c), file)});
    if (o.contains("bands")) {
      const json& bs = List(o, "bands", where, file);
      for (std::size_t b = 0; b < bs.size(); ++b) {
        const std::string bw = where + "." + Index("bands", b);
        ResultFigures::Band fb{Number(bs[b], "lo_hz", bw, file), Number(bs[b], "hi_hz", bw, file),
                               Variance(bs[b], "variance", bw, file), {}};
        if (!(std::isfinite(fb.lo_hz) && std::isfinite(fb.hi_hz) && 0.0 < fb.lo_hz && fb.lo_hz < fb.hi_hz))
          throw InputError(bw, file + ": " + bw + ": [" + Excerpt(bs[b]["lo_hz"].dump()) + ", " +
                                   Excerpt(bs[b]["hi_hz"].dump()) + "] Hz is not a band (0 < lo_hz < hi_hz)");
        const json& bc = List(bs[b], "contributors", bw, file);
        for (std::size_t c = 0; c < bc.size(); ++c)
          fb.contributor_variance.push_back(Variance(bc[c], "variance", bw + "." + Index("contributors", c), file));
        fo.bands.push_back(std::move(fb));
      }
    }
    r.outputs.push_back(std::move(fo));
  }
  // summary.json lists `parameters` when the budget has them.
  if (j.contains("parameters")) {
    const json& ps = List(j, "parameters", "", file);
    for (std::size_t p = 0; p < ps.size() && p < kMaxParameters; ++p) {
      const std::string where = Index("parameters", p);
      ParameterOutline po;
      po.name = Text(ps[p], "name", where, file);
      po.value = Number(ps[p], "value", where, file);
      po.unit = Text(ps[p], "unit", where, file);
      po.expression = Text(ps[p], "expression", where, file);
      po.derived = ps[p].contains("derived") && ps[p]["derived"].is_boolean() && ps[p]["derived"].get<bool>();
      r.parameters.push_back(std::move(po));
    }
  }
  return r;
}

std::string ComparisonJson(const Comparison& cmp) {
  json j;
  j["a"] = cmp.label_a;
  j["b"] = cmp.label_b;
  j["conventions"] = {{"difference", "rms_b - rms_a, in the output's unit"},
                      {"ratio", "rms_b / rms_a (null when either side is negligible, or both are 0)"},
                      {"negligible", "variance below 1e-6 of its total's (the output's, or the band's)"},
                      {"variance_change_of_total",
                       "(variance_b - variance_a) / the larger total variance of the output"}};
  json figures = json::array();
  for (const auto& f : cmp.figures) figures.push_back(FigureJson(f));
  j["figures"] = figures;
  json largest = json::array();
  for (const auto& f : cmp.LargestChanges()) largest.push_back(FigureJson(f));
  j["largest_changes"] = largest;
  j["unmatched"] = cmp.unmatched;
  if (!cmp.parameters.empty()) {
    json parameters = json::array();
    for (const ParameterChange& p : cmp.parameters) parameters.push_back({{"name", p.name}, {"a", p.a}, {"b", p.b}});
    j["parameters_differ"] = parameters;
  }
  if (cmp.tolerance) {  // the regression gate's verdict
    j["tolerance"] = *cmp.tolerance;
    json moved = json::array();
    for (const auto& f : cmp.Moved(*cmp.tolerance)) moved.push_back(FigureJson(f));
    j["moved"] = moved;
  }
  return j.dump(2) + "\n";
}

std::string ComparisonCsv(const Comparison& cmp) {
  std::ostringstream os;
  os << "output,unit,contributor,band,rms_a,rms_b,difference,ratio,variance_change_of_total\n";
  for (const auto& f : cmp.figures)
    os << CsvField(f.output) << ',' << CsvField(f.unit) << ',' << CsvField(f.contributor) << ','
       << CsvField(f.band) << ',' << Num(f.rms_a) << ',' << Num(f.rms_b) << ',' << Num(f.difference) << ','
       << (f.ratio ? Num(*f.ratio) : std::string()) << ',' << Num(f.variance_change_of_total) << '\n';
  return os.str();
}

}  // namespace deb
