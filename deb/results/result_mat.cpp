#include "deb/results/result_mat.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include "deb/budget/groups.h"
#include "deb/formats/mat_file.h"
#include "deb/version.h"

namespace deb {
namespace {

using formats::MatValue;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kMaxMatlabName = 63;  // MATLAB's namelengthmax

Eigen::Index Rows(std::size_t n) { return static_cast<Eigen::Index>(n); }

// grid x contributors (or references): column k is traces(k).
template <class Items, class Trace>
MatValue Traces(std::size_t grid, const Items& items, Trace trace) {
  Eigen::MatrixXd m(Rows(grid), Rows(items.size()));
  for (std::size_t k = 0; k < items.size(); ++k) {
    const std::vector<double>& t = trace(items[k]);
    for (std::size_t i = 0; i < grid; ++i) m(Rows(i), Rows(k)) = t[i];
  }
  return MatValue::Matrix(std::move(m));
}

template <class Items, class Figure>
MatValue Column(const Items& items, Figure figure) {
  std::vector<double> v;
  for (const auto& item : items) v.push_back(figure(item));
  return MatValue::Column(v);
}

template <class Items, class Name>
MatValue NameList(const Items& items, Name name) {
  std::vector<std::string> v;
  for (const auto& item : items) v.push_back(name(item));
  return MatValue::Names(std::move(v));
}

MatValue Tones(const OutputResult& o) {
  std::vector<std::string> names;
  std::vector<double> f_hz, variance;
  for (const ContributorResult& c : o.contributors)
    for (const ContributorResult::Tone& t : c.tones) {
      names.push_back(c.name);
      f_hz.push_back(t.f_hz);
      variance.push_back(t.variance);
    }
  MatValue s = MatValue::Struct();
  s.Add("contributor", MatValue::Names(names)).Add("f_hz", MatValue::Column(f_hz)).Add("variance", MatValue::Column(variance));
  return s;
}

MatValue Bands(const OutputResult& o) {
  Eigen::MatrixXd per(Rows(o.bands.size()), Rows(o.contributors.size()));
  for (std::size_t b = 0; b < o.bands.size(); ++b)
    for (std::size_t c = 0; c < o.contributors.size(); ++c)
      per(Rows(b), Rows(c)) = o.bands[b].contributor_variance[c];
  MatValue s = MatValue::Struct();
  s.Add("lo_hz", Column(o.bands, [](const BandResult& b) { return b.band.lo_hz; }))
      .Add("hi_hz", Column(o.bands, [](const BandResult& b) { return b.band.hi_hz; }))
      .Add("variance", Column(o.bands, [](const BandResult& b) { return b.variance; }))
      .Add("contributor_variance", MatValue::Matrix(std::move(per)));
  return s;
}

MatValue BandRequirements(const OutputResult& o) {
  const auto& r = o.band_requirements;
  MatValue s = MatValue::Struct();
  s.Add("lo_hz", Column(r, [](const BandRequirementResult& b) { return b.requirement.lo_hz; }))
      .Add("hi_hz", Column(r, [](const BandRequirementResult& b) { return b.requirement.hi_hz; }))
      .Add("rms_max", Column(r, [](const BandRequirementResult& b) { return b.requirement.rms_max; }))
      .Add("variance", Column(r, [](const BandRequirementResult& b) { return b.variance; }))
      .Add("rms", Column(r, [](const BandRequirementResult& b) { return b.rms(); }))
      .Add("pass", Column(r, [](const BandRequirementResult& b) { return b.pass() ? 1.0 : 0.0; }));
  return s;
}

MatValue Groups(const OutputResult& o) {
  const std::vector<GroupResult> groups = ComputeGroups(o);
  MatValue s = MatValue::Struct();
  s.Add("name", NameList(groups, [](const GroupResult& g) { return g.path; }))
      .Add("depth", Column(groups, [](const GroupResult& g) { return static_cast<double>(g.depth); }))
      .Add("variance", Column(groups, [](const GroupResult& g) { return g.variance; }))
      .Add("rms", Column(groups, [](const GroupResult& g) { return std::sqrt(g.variance); }))
      .Add("share", Column(groups, [](const GroupResult& g) { return g.share; }));
  return s;
}

MatValue References(const OutputResult& o, std::size_t grid) {
  const auto& r = o.references;
  MatValue s = MatValue::Struct();
  s.Add("name", NameList(r, [](const ReferenceResult& x) { return x.name; }))
      .Add("psd", Traces(grid, r, [](const ReferenceResult& x) -> const std::vector<double>& { return x.psd; }))
      .Add("cps", Traces(grid, r, [](const ReferenceResult& x) -> const std::vector<double>& { return x.cps; }))
      .Add("variance", Column(r, [](const ReferenceResult& x) { return x.variance; }))
      .Add("budget_variance", Column(r, [](const ReferenceResult& x) { return x.budget_variance; }))
      .Add("covered_lo_hz", Column(r, [](const ReferenceResult& x) { return x.covered_lo_hz; }))
      .Add("covered_hi_hz", Column(r, [](const ReferenceResult& x) { return x.covered_hi_hz; }));
  return s;
}

MatValue OutputStruct(const OutputResult& o, std::size_t grid) {
  const auto& cs = o.contributors;
  const auto psd = [](const ContributorResult& c) -> const std::vector<double>& { return c.psd; };
  const auto cps = [](const ContributorResult& c) -> const std::vector<double>& { return c.cps; };
  MatValue s = MatValue::Struct();
  s.Add("name", MatValue::Text(o.name))
      .Add("signal", MatValue::Text(o.signal))
      .Add("unit", MatValue::Text(o.unit))
      .Add("contributors", NameList(cs, [](const ContributorResult& c) { return c.name; }))
      .Add("sources", NameList(cs, [](const ContributorResult& c) { return c.source; }))
      .Add("paths", NameList(cs, [](const ContributorResult& c) { return c.path; }))
      .Add("groups_of_contributors", NameList(cs, [](const ContributorResult& c) { return c.group; }))
      .Add("psd", Traces(grid, cs, psd))
      .Add("cps", Traces(grid, cs, cps))
      .Add("total_psd", MatValue::Column(o.total_psd))
      .Add("total_cps", MatValue::Column(o.total_cps))
      .Add("variance", MatValue::Scalar(o.variance))
      .Add("rms", MatValue::Scalar(o.rms()))
      .Add("rms_max", MatValue::Scalar(o.rms_max.value_or(kNaN)))
      .Add("pass", MatValue::Scalar(o.AllPass() ? 1.0 : 0.0))
      .Add("contributor_variance", Column(cs, [](const ContributorResult& c) { return c.variance; }))
      .Add("contributor_rms", Column(cs, [](const ContributorResult& c) { return std::sqrt(c.variance); }))
      .Add("share", Column(cs, [&o](const ContributorResult& c) { return o.variance > 0 ? c.variance / o.variance : 0.0; }))
      .Add("exact_variance", Column(cs, [](const ContributorResult& c) { return c.exact_variance.value_or(kNaN); }))
      .Add("tones", Tones(o))
      .Add("bands", Bands(o))
      .Add("band_requirements", BandRequirements(o))
      .Add("groups", Groups(o))
      .Add("references", References(o, grid));
  return s;
}

}  // namespace

std::string MatlabName(const std::string& name, std::vector<std::string>& taken) {
  std::string base;
  for (const char ch : name) {
    const unsigned char u = static_cast<unsigned char>(ch);
    base += u < 0x80 && (std::isalnum(u) || ch == '_') ? ch : '_';
  }
  if (base.empty() || !std::isalpha(static_cast<unsigned char>(base[0]))) base = "x" + base;
  base = base.substr(0, kMaxMatlabName);
  std::string out = base;
  for (int k = 2; std::find(taken.begin(), taken.end(), out) != taken.end(); ++k) {
    const std::string suffix = "_" + std::to_string(k);
    out = base.substr(0, kMaxMatlabName - suffix.size()) + suffix;
  }
  taken.push_back(out);
  return out;
}

void WriteResultMat(const BudgetResult& result, const std::string& file) {
  const std::size_t grid = result.grid.size();
  MatValue outputs = MatValue::Struct();
  std::vector<std::string> taken, names;
  for (const OutputResult& o : result.outputs) {
    outputs.Add(MatlabName(o.name, taken), OutputStruct(o, grid));
    names.push_back(o.name);
  }
  std::vector<std::pair<std::string, MatValue>> variables;
  variables.emplace_back("f_hz", MatValue::Column(result.grid.f_hz()));
  variables.emplace_back("budget_name", MatValue::Text(result.outline.name));
  variables.emplace_back("deb_version", MatValue::Text(DEB_VERSION));
  variables.emplace_back("output_names", MatValue::Names(names));
  variables.emplace_back("output_fields", MatValue::Names(taken));
  variables.emplace_back("outputs", std::move(outputs));
  variables.emplace_back("warnings", MatValue::Names(result.warnings));
  formats::WriteMatFile(file, variables, "written by deb " DEB_VERSION);
}

}  // namespace deb
