#include "deb/budget/comparison.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/core/number_text.h"
#include "deb/core/rounding_zero.h"

namespace deb {
namespace {

std::string BandLabel(double lo, double hi) {
  std::ostringstream os;
  os << lo << "-" << hi << " Hz";
  return os.str();
}

bool SameEdge(double x, double y) { return std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y)); }

bool SameBand(const ResultFigures::Band& x, const ResultFigures::Band& y) {
  return SameEdge(x.lo_hz, y.lo_hz) && SameEdge(x.hi_hz, y.hi_hz);
}

// ref_a, ref_b: the variance the figure is negligible against (its output's
// total; a band's total for the band's contributors; itself for a band's total).
ComparedFigure Figure(const ResultFigures::Output& oa, const ResultFigures::Output& ob, const std::string& contributor,
                      const std::string& band, double var_a, double var_b, double ref_a, double ref_b) {
  const double total = std::max(oa.variance, ob.variance);
  ComparedFigure f;
  f.output = oa.name;
  f.unit = oa.unit;
  f.contributor = contributor;
  f.band = band;
  // A part computed as rounding reads 0, as in the run report's tables
  // (nizamoglu2015_h0's floor on beta_velocity read 6.144e-13 here, 0 there).
  var_a = WithoutRounding(var_a, oa.variance);
  var_b = WithoutRounding(var_b, ob.variance);
  f.rms_a = std::sqrt(var_a);
  f.rms_b = std::sqrt(var_b);
  f.difference = f.rms_b - f.rms_a;
  f.negligible_a = var_a < kNegligibleShare * ref_a || var_a <= 0.0;
  f.negligible_b = var_b < kNegligibleShare * ref_b || var_b <= 0.0;
  if (f.rms_a > 0.0 && !f.negligible_a && !f.negligible_b) f.ratio = f.rms_b / f.rms_a;
  f.variance_change_of_total = total > 0.0 ? (var_b - var_a) / total : 0.0;
  return f;
}

template <typename T, typename Key>
const T* Find(const std::vector<T>& items, const Key& key) {
  for (const T& item : items)
    if (key(item)) return &item;
  return nullptr;
}

}  // namespace

namespace {

std::string ParameterText(const ParameterOutline& p) {
  return SignificantText(p.value, 6) + (p.unit.empty() ? "" : " " + p.unit) + (p.derived ? " = " + p.expression : "");
}

std::vector<ParameterChange> ParameterChanges(const std::vector<ParameterOutline>& a,
                                              const std::vector<ParameterOutline>& b) {
  std::vector<ParameterChange> changes;
  const auto find = [](const std::vector<ParameterOutline>& list, const std::string& name) -> const ParameterOutline* {
    for (const ParameterOutline& p : list)
      if (p.name == name) return &p;
    return nullptr;
  };
  for (const ParameterOutline& pa : a) {
    const ParameterOutline* pb = find(b, pa.name);
    const std::string ta = ParameterText(pa), tb = pb ? ParameterText(*pb) : "";
    if (ta != tb) changes.push_back({pa.name, ta, tb});
  }
  for (const ParameterOutline& pb : b)
    if (!find(a, pb.name)) changes.push_back({pb.name, "", ParameterText(pb)});
  return changes;
}

}  // namespace

ResultFigures FiguresOf(const std::string& label, const BudgetResult& result) {
  ResultFigures r;
  r.label = label;
  for (const OutputResult& o : result.outputs) {
    ResultFigures::Output fo;
    fo.name = o.name;
    fo.unit = o.unit;
    fo.variance = o.variance;
    fo.rms_max = o.rms_max;
    for (const ContributorResult& c : o.contributors) fo.contributors.push_back({c.name, c.variance});
    for (const BandResult& b : o.bands) fo.bands.push_back({b.band.lo_hz, b.band.hi_hz, b.variance, b.contributor_variance});
    r.outputs.push_back(std::move(fo));
  }
  r.parameters = result.outline.parameters;
  return r;
}

Comparison Compare(const ResultFigures& a, const ResultFigures& b) {
  Comparison cmp;
  cmp.label_a = a.label;
  cmp.label_b = b.label;
  cmp.parameters = ParameterChanges(a.parameters, b.parameters);
  for (const auto& oa : a.outputs) {
    const auto* ob = Find(b.outputs, [&](const ResultFigures::Output& o) { return o.name == oa.name; });
    if (!ob) {
      cmp.unmatched.push_back("output '" + oa.name + "' is only in " + a.label);
      continue;
    }
    if (ob->unit != oa.unit) {
      cmp.unmatched.push_back("output '" + oa.name + "' is in " + oa.unit + " in " + a.label + " but in " + ob->unit +
                              " in " + b.label + ": not compared");
      continue;
    }
    cmp.figures.push_back(Figure(oa, *ob, "total", "", oa.variance, ob->variance, oa.variance, ob->variance));
    for (const auto& ca : oa.contributors) {
      const auto* cb = Find(ob->contributors, [&](const ResultFigures::Contributor& c) { return c.name == ca.name; });
      if (!cb) {
        cmp.unmatched.push_back("contributor '" + ca.name + "' on output '" + oa.name + "' is only in " + a.label);
        continue;
      }
      cmp.figures.push_back(Figure(oa, *ob, ca.name, "", ca.variance, cb->variance, oa.variance, ob->variance));
    }
    for (const auto& cb : ob->contributors)
      if (!Find(oa.contributors, [&](const ResultFigures::Contributor& c) { return c.name == cb.name; }))
        cmp.unmatched.push_back("contributor '" + cb.name + "' on output '" + oa.name + "' is only in " + b.label);
    for (const auto& ba : oa.bands) {
      const auto* bb = Find(ob->bands, [&](const ResultFigures::Band& x) { return SameBand(x, ba); });
      const std::string label = BandLabel(ba.lo_hz, ba.hi_hz);
      if (!bb) {
        cmp.unmatched.push_back("band " + label + " of output '" + oa.name + "' is only in " + a.label);
        continue;
      }
      const auto in_band = [&](ComparedFigure f) {
        f.band_lo_hz = ba.lo_hz;
        f.band_hi_hz = ba.hi_hz;
        return f;
      };
      cmp.figures.push_back(
          in_band(Figure(oa, *ob, "total", label, ba.variance, bb->variance, ba.variance, bb->variance)));
      for (std::size_t c = 0; c < oa.contributors.size() && c < ba.contributor_variance.size(); ++c) {
        const std::string& name = oa.contributors[c].name;
        for (std::size_t d = 0; d < ob->contributors.size() && d < bb->contributor_variance.size(); ++d)
          if (ob->contributors[d].name == name)
            cmp.figures.push_back(in_band(Figure(oa, *ob, name, label, ba.contributor_variance[c],
                                                 bb->contributor_variance[d], ba.variance, bb->variance)));
      }
    }
    for (const auto& bb : ob->bands)
      if (!Find(oa.bands, [&](const ResultFigures::Band& x) { return SameBand(x, bb); }))
        cmp.unmatched.push_back("band " + BandLabel(bb.lo_hz, bb.hi_hz) + " of output '" + oa.name + "' is only in " +
                                b.label);
  }
  for (const auto& ob : b.outputs)
    if (!Find(a.outputs, [&](const ResultFigures::Output& o) { return o.name == ob.name; }))
      cmp.unmatched.push_back("output '" + ob.name + "' is only in " + b.label);
  return cmp;
}

bool ComparedFigure::MovedBy(double rel) const {
  if (negligible_a && negligible_b) return false;
  if (negligible_a != negligible_b) return true;
  return std::abs(rms_b - rms_a) > rel * rms_a;
}

std::vector<ComparedFigure> Comparison::Moved(double rel) const {
  std::vector<ComparedFigure> out;
  for (const ComparedFigure& f : figures)
    if (f.MovedBy(rel)) out.push_back(f);
  return out;
}

std::vector<ComparedFigure> Comparison::LargestChanges(std::size_t count) const {
  std::vector<ComparedFigure> out;
  std::vector<std::string> outputs;
  for (const auto& f : figures)
    if (std::find(outputs.begin(), outputs.end(), f.output) == outputs.end()) outputs.push_back(f.output);
  for (const std::string& name : outputs) {
    std::vector<ComparedFigure> of;
    for (const auto& f : figures)
      if (f.output == name && f.band.empty() && f.contributor != "total") of.push_back(f);
    std::stable_sort(of.begin(), of.end(), [](const ComparedFigure& x, const ComparedFigure& y) {
      return std::abs(x.variance_change_of_total) > std::abs(y.variance_change_of_total);
    });
    if (of.size() > count) of.resize(count);
    out.insert(out.end(), of.begin(), of.end());
  }
  return out;
}

}  // namespace deb
