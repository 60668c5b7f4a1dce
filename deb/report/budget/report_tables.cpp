#include "deb/report/budget/report_tables.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "deb/budget/allocation.h"
#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/core/number_text.h"
#include "deb/report/budget/band_text.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/plot.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb::report {
namespace {


// Characters of a UTF-8 string (for alignment of µ, –, …).
std::size_t Width(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

std::string Shorten(const std::string& s, std::size_t max) {
  if (Width(s) <= max) return s;
  std::string out;
  std::size_t chars = 0;
  for (char c : s) {
    if ((c & 0xC0) != 0x80 && ++chars == max) break;
    out += c;
  }
  return out + "…";
}

std::string MarkdownEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|' || c == '*' || c == '_' || c == '\\' || c == '`' || c == '[' || c == ']' || c == '<') out += '\\';
    out += c;
  }
  return out;
}

bool Emphasised(const Table& t, std::size_t r, std::size_t c) {
  return r < t.emphasis.size() && c < t.emphasis[r].size() && t.emphasis[r][c];
}

}  // namespace

Table SummaryTable(const BudgetResult& result, int digits) {
  Table t;
  t.title = "Summary";
  t.header = {"output", "unit", "RMS", "requirement", "margin", "status", "largest contributor"};
  t.numeric = {false, false, true, true, true, false, false};
  for (const OutputResult& o : result.outputs) {
    std::string largest = "–";
    if (!o.contributors.empty()) {
      const std::size_t c = ShareOrder(o).front();
      largest = o.contributors[c].name + " (" + Share(o.contributors[c].variance, o.variance) + ")";
    }
    t.rows.push_back({o.name, UnitText(o.unit), Sig(o.rms(), digits), o.rms_max ? Short(*o.rms_max) : "–",
                      o.rms_max ? Sig(*o.rms_max - o.rms(), digits) : "–", o.rms_max ? (o.pass() ? "pass" : "FAIL") : "–",
                      largest});
    t.emphasis.push_back({false, false, false, false, false, o.rms_max && !o.pass(), false});
    for (const BandRequirementResult& b : o.band_requirements) {
      std::string in_band = "–";
      if (!o.contributors.empty() && b.variance > 0.0) {
        const std::vector<double> v = VarianceWithin(o, result.grid, b.requirement.lo_hz, b.requirement.hi_hz);
        const std::size_t c = static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin());
        in_band = o.contributors[c].name + " (" + Share(v[c], b.variance) + ")";
      }
      t.rows.push_back({o.name + ", " + BandText(b.requirement.lo_hz, b.requirement.hi_hz), UnitText(o.unit),
                        Sig(b.rms(), digits), Short(b.requirement.rms_max), Sig(b.requirement.rms_max - b.rms(), digits),
                        b.pass() ? "pass" : "FAIL", in_band});
      t.emphasis.push_back({false, false, false, false, false, !b.pass(), false});
    }
  }
  return t;
}

Table ContributorTable(const OutputResult& o, int digits) {
  Table t;
  t.title = "Contributors to " + o.name + " [" + UnitText(o.unit) + "]" +
            (o.metric ? ", " + o.metric->Describe() : std::string());
  t.header = {"contributor", "source", "path", "RMS", "share", "exact RMS"};
  t.numeric = {false, false, false, true, true, true};
  // A failing output: the reduction of each contributor's RMS that meets the
  // limit, alone, or together with the rest of the smallest set of largest
  // contributors that can (failure_guidance.h); else the factor k on the
  // source's PSD that puts the output at its limit.
  const bool fails = o.rms_max && !o.pass();
  // The smallest set, and the set one larger where there is one (the
  // guidance sentence's trade-off).
  std::vector<ContributorReduction> reductions;
  if (fails) {
    reductions = Reductions(o);
    t.title += "; must drop: the factor on the contributor's RMS that meets the limit alone, or \"each of "
               "top n\" with the n largest";
  }
  if (o.rms_max) {
    t.header.push_back(fails ? "must drop" : "allocation k");
    t.numeric.push_back(true);
  }
  t.header.push_back("note");
  t.numeric.push_back(false);
  for (std::size_t c : ShareOrder(o)) {
    const ContributorResult& cr = o.contributors[c];
    std::string note = cr.exact_note;
    // A contributor of tones alone: its variance is exact on any grid (no note).
    double tone_variance = 0.0;
    for (const ContributorResult::Tone& t : cr.tones) tone_variance += t.variance;
    const bool tones_only = !cr.tones.empty() && tone_variance >= cr.variance * (1.0 - 1e-12);
    if (cr.exact_variance && *cr.exact_variance > 0.0 && !tones_only)
      note = "grid holds " + Sig(100.0 * cr.variance / *cr.exact_variance, digits) + " % of the exact variance";
    // A contributor the model does not couple to the output (by symmetry)
    // computes as rounding: 0, as in the channel table.
    const double variance = WithoutRounding(cr.variance, o.variance);
    std::vector<std::string> row = {cr.name, cr.source, cr.path, Sig(std::sqrt(variance), digits),
                                    Share(variance, o.variance),
                                    cr.exact_variance ? Sig(std::sqrt(*cr.exact_variance), digits) : "–"};
    if (fails) {
      const Allocation a = AllocationFactor(o, c);
      const auto in = [c](const ContributorReduction& r) {
        return std::find(r.contributors.begin(), r.contributors.end(), c) != r.contributors.end();
      };
      const ContributorReduction& least = reductions.front();
      const std::string top = ", each of top ";
      if (a.factor && *a.factor > 0.0)
        row.push_back(Sig(1.0 / std::sqrt(*a.factor), digits) + "×");
      else if (in(least) && least.rms_factor)
        row.push_back(Sig(*least.rms_factor, digits) + "×" + top + std::to_string(least.contributors.size()));
      else if (in(least))
        row.push_back("remove, with top " + std::to_string(least.contributors.size()));
      else if (reductions.size() > 1 && in(reductions[1]) && reductions[1].rms_factor)
        row.push_back(Sig(*reductions[1].rms_factor, digits) + "×" + top + std::to_string(reductions[1].contributors.size()));
      else
        row.push_back("–");
    } else if (o.rms_max) {
      const Allocation a = AllocationFactor(o, c);
      row.push_back(a.factor ? Sig(*a.factor, digits) : "–");
      if (!a.factor) note += std::string(note.empty() ? "" : "; ") + "no allocation: " + a.note;
    }
    row.push_back(note);
    t.rows.push_back(row);
  }
  std::vector<std::string> total = {"total", "", "", Sig(o.rms(), digits), o.variance > 0 ? "100 %" : "–", ""};
  if (o.rms_max) total.push_back("");
  total.push_back("");
  t.rows.push_back(total);
  return t;
}

std::string GuidanceText(const OutputResult& o, const FrequencyGrid& grid) {
  const std::optional<FailureGuidance> g = GuideFailure(o, grid);
  return g ? GuidanceSentence(o, *g, UnitText(o.unit)) + "." : std::string();
}

Table ModeTable(const OutputResult& o) {
  Table t;
  t.title = "Modes carrying the variance of " + o.name +
            " (each mode's cross-spectrum with the output; with the other modes' row, a contributor's shares add "
            "up to 100 %)";
  t.header = {"contributor", "mode", "f_n [Hz]", "zeta", "share", "of"};
  t.numeric = {false, true, true, true, true, false};
  for (const ContributorResult& c : o.contributors) {
    const std::string of = c.top_modes_of == ModeSplit::kExactVariance ? "exact variance" : "grid variance";
    double listed = 0.0;
    for (const ModeShare& m : c.top_modes) {
      listed += m.share;
      t.rows.push_back({c.name, std::to_string(m.mode), Sig(m.f_hz, 4), Sig(m.zeta, 2),
                        // a mode the output does not see, computed as rounding (1e-36): 0
                        RoundingZero(std::abs(m.share), 1.0) ? std::string("0 %") : Share(m.share, 1.0), of});
    }
    // The modes beyond the listed ones (summary.json's top_modes are the
    // ten largest): what they hold together, where it shows.
    if (!c.top_modes.empty() && std::abs(1.0 - listed) >= 5e-5)
      t.rows.push_back({c.name, "the others", "", "", Share(1.0 - listed, 1.0), of});
  }
  return t;
}

Table ChannelTable(const OutputResult& o, int digits) {
  Table t;
  t.title = "Source channels of " + o.name + " [" + UnitText(o.unit) +
            "]: each channel's part |H|² S of its contributor (breakdown: channels)";
  t.header = {"contributor", "channel", "RMS", "share", "of contributor"};
  t.numeric = {false, false, true, true, true};
  for (std::size_t c : ShareOrder(o)) {
    const ContributorResult& cr = o.contributors[c];
    if (cr.channels.empty()) continue;
    std::vector<const ContributorResult::ChannelPart*> parts;
    for (const ContributorResult::ChannelPart& p : cr.channels) parts.push_back(&p);
    std::stable_sort(parts.begin(), parts.end(), [](const auto* a, const auto* b) { return a->variance > b->variance; });
    for (const ContributorResult::ChannelPart* p : parts) {
      const double v = WithoutRounding(p->variance, cr.variance);
      t.rows.push_back({cr.name, p->channel, v > 0.0 ? Sig(std::sqrt(v), digits) : "0", Share(v, o.variance),
                        Share(v, cr.variance)});
    }
    if (cr.cross_variance != 0.0)
      t.rows.push_back({cr.name, "cross terms (variance)", Sig(cr.cross_variance, digits) + " " + Squared(UnitText(VarianceUnit(o.unit))),
                        o.variance > 0.0 ? Sig(100.0 * cr.cross_variance / o.variance, 3) + " %" : "–",
                        cr.variance > 0.0 ? Sig(100.0 * cr.cross_variance / cr.variance, 3) + " %" : "–"});
  }
  return t;
}

Table GroupTable(const OutputResult& o, int digits) {
  Table t;
  t.title = "Groups of " + o.name + " [" + UnitText(o.unit) + "]: each the sum of its members at any depth";
  t.header = {"group", "members", "RMS", "share"};
  t.numeric = {false, false, true, true};
  for (const BandResult& b : o.bands) {
    t.header.push_back(BandText(b.band.lo_hz, b.band.hi_hz));
    t.numeric.push_back(true);
  }
  for (const GroupResult& g : ComputeGroups(o)) {
    std::string members;
    for (std::size_t c : g.contributors) members += (members.empty() ? "" : ", ") + o.contributors[c].name;
    for (const std::string& sub : g.subgroups) members += (members.empty() ? "" : ", ") + sub.substr(sub.rfind('/') + 1) + "/";
    std::vector<std::string> row = {std::string(2 * static_cast<std::size_t>(g.depth), ' ') + g.name, members,
                                    Sig(std::sqrt(g.variance), digits), Share(g.variance, o.variance)};
    for (double v : g.band_variance) row.push_back(Sig(std::sqrt(std::max(v, 0.0)), digits));
    t.rows.push_back(std::move(row));
  }
  return t;
}

Table ReferenceTable(const OutputResult& o, int digits) {
  Table t;
  t.title = "Does the budget explain the measurement? " + o.name + " [" + UnitText(o.unit) +
            "]: measured against budget RMS; unexplained = √max(measured² − budget², 0)";
  t.header = {"reference", "band", "budget RMS", "measured RMS", "measured / budget", "unexplained RMS"};
  t.numeric = {false, false, true, true, true, true};
  const auto row = [&](const std::string& ref, const std::string& band, double budget, double measured) {
    t.rows.push_back({ref, band, Sig(std::sqrt(budget), digits), Sig(std::sqrt(measured), digits),
                      budget > 0.0 ? Sig(std::sqrt(measured / budget), digits) : "–",
                      Sig(std::sqrt(std::max(measured - budget, 0.0)), digits)});
  };
  // The measured data's span to 4 digits (0.201183–1925.04 Hz was more
  // than a reader needs), without trailing zeros ("1", not "1.000").
  const auto edge = [](double f) { return Short(std::stod(Sig(f, 4))); };
  for (const ReferenceResult& r : o.references) {
    double budget_in_bands = 0.0, measured_in_bands = 0.0;
    std::vector<std::pair<double, double>> listed;
    for (std::size_t b = 0; b < o.bands.size(); ++b)
      if (r.band_variance[b]) {
        row(r.name, BandText(o.bands[b].band.lo_hz, o.bands[b].band.hi_hz), o.bands[b].variance, *r.band_variance[b]);
        budget_in_bands += o.bands[b].variance;
        measured_in_bands += *r.band_variance[b];
        listed.push_back({o.bands[b].band.lo_hz, o.bands[b].band.hi_hz});
      }
    // The covered range outside the bands listed (the ends of partly covered
    // bands): what the rows above leave out of the covered row below, where
    // it shows (wafer_stage's 0.2012-1 Hz held most of the unexplained 2.450 nm).
    if (!listed.empty()) {
      std::sort(listed.begin(), listed.end());
      std::string parts;
      double at = r.covered_lo_hz;
      const auto part = [&](double lo, double hi) {
        if (hi > lo * (1 + 1e-9)) parts += (parts.empty() ? "" : ", ") + edge(lo) + "–" + edge(hi) + " Hz";
      };
      for (const auto& [lo, hi] : listed) {
        part(at, std::min(lo, r.covered_hi_hz));
        at = std::max(at, hi);
      }
      part(at, r.covered_hi_hz);
      const double budget_rest = std::max(r.budget_variance - budget_in_bands, 0.0);
      const double measured_rest = std::max(r.variance - measured_in_bands, 0.0);
      if (!parts.empty() && (budget_rest > 1e-6 * r.budget_variance || measured_rest > 1e-6 * r.variance))
        row(r.name, "rest: " + parts, budget_rest, measured_rest);
    }
    row(r.name, "covered " + edge(r.covered_lo_hz) + "–" + edge(r.covered_hi_hz) + " Hz", r.budget_variance,
        r.variance);
  }
  return t;
}

std::vector<std::string> MeasurementWarnings(const BudgetResult& result, int digits) {
  std::vector<std::string> out;
  for (const OutputResult& o : result.outputs)
    for (const ReferenceResult& r : o.references) {
      if (!(r.budget_variance > 0.0) || !(r.variance > 0.0)) continue;
      const double ratio = std::sqrt(r.variance / r.budget_variance);
      if (ratio <= kReferenceMismatch && ratio >= 1.0 / kReferenceMismatch) continue;
      const std::string unit = UnitText(o.unit);
      const std::string span = Sig(r.covered_lo_hz, 4) + "–" + Sig(r.covered_hi_hz, 4) + " Hz";
      const std::string head = "Measured " + o.name + " (" + r.name + "): " + Sig(ratio, 3) +
                               "× the budget's RMS over " + span;
      if (ratio > 1.0)
        out.push_back(head + "; the budget explains " + Share(r.budget_variance, r.variance) +
                      " of the measured variance (" + Sig(std::sqrt(r.variance - r.budget_variance), digits) + " " +
                      unit + " RMS unexplained). The verdict covers the budget's contributors only.");
      else
        out.push_back(head + ": the budget is pessimistic there, and a failing verdict may overstate the problem.");
    }
  return out;
}

Table CovarianceTable(const CovarianceResult& cov, int digits) {
  Table t;
  t.title = "Covariance of outputs (each pair; the matrices are in summary.json)";
  // The exact column only where there is an exact matrix (summary.json's exact_note says why not).
  const bool exact = cov.exact_matrix.has_value();
  t.header = {"output a", "output b", "correlation", "covariance"};
  t.numeric = {false, false, true, true};
  if (exact) {
    t.header.push_back("exact correlation");
    t.numeric.push_back(true);
  }
  t.header.push_back("largest contributor (its part)");
  t.numeric.push_back(false);
  // A correlation below kRoundingCorrelation is the rounding of a pair the
  // model leaves uncorrelated (by symmetry, or disjoint contributors): shown
  // as such, not as data (a 1e-18 correlation with a "largest contributor").
  bool rounding = false, cancels = false;
  const auto correlation = [&rounding](const Eigen::MatrixXd& m, Eigen::Index a, Eigen::Index b) {
    const double d = std::sqrt(m(a, a) * m(b, b));
    if (!(d > 0.0)) return std::string("–");
    const double rho = m(a, b) / d;
    if (rho != 0.0 && std::abs(rho) < kRoundingCorrelation) {
      rounding = true;
      return std::string("≈ 0");
    }
    return Sig(rho, 3);
  };
  const auto negligible = [&cov](Eigen::Index a, Eigen::Index b) {
    const double d = std::sqrt(cov.matrix(a, a) * cov.matrix(b, b));
    return d > 0.0 && cov.matrix(a, b) != 0.0 && std::abs(cov.matrix(a, b)) < kRoundingCorrelation * d;
  };
  const Eigen::Index n = cov.matrix.rows();
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = a + 1; b < n; ++b) {
      const std::size_t ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
      const std::string unit = cov.units[ia] == cov.units[ib]
                                   ? Squared(UnitText(VarianceUnit(cov.units[ia])))
                                   : UnitText(cov.units[ia]) + "·" + UnitText(cov.units[ib]);
      std::string largest = "–";
      double part = 0.0;
      for (const ContributorCovariance& c : cov.contributors)
        if (std::abs(c.matrix(a, b)) > std::abs(part)) {
          part = c.matrix(a, b);
          largest = c.name;
        }
      const bool zero = negligible(a, b);
      if (zero) {
        largest = "–";
      } else if (part != 0.0 && cov.matrix(a, b) != 0.0) {
        const double percent = 100.0 * part / cov.matrix(a, b);
        largest += " (" + Sig(percent, 3) + " %)";
        cancels = cancels || percent > 100.0 || percent < 0.0;
      }
      std::vector<std::string> row = {cov.outputs[ia], cov.outputs[ib], correlation(cov.matrix, a, b),
                                      (zero ? std::string("≈ 0") : Sig(cov.matrix(a, b), digits)) + " " + unit};
      if (exact) row.push_back(correlation(*cov.exact_matrix, a, b));
      row.push_back(largest);
      t.rows.push_back(std::move(row));
    }
  if (rounding)
    t.notes.push_back("≈ 0: a correlation below " + Sig(kRoundingCorrelation, 1) +
                      " in size, the rounding of a pair the model leaves uncorrelated (summary.json keeps the "
                      "computed value).");
  if (cancels)
    t.notes.push_back("A part above 100 % (or below 0): contributors of opposite sign partly cancel in that "
                      "covariance.");
  return t;
}

Table BandTable(const OutputResult& o, int digits) {
  Table t;
  t.title = "RMS of " + o.name + " per band [" + UnitText(o.unit) + "]";
  t.header = {"contributor"};
  t.numeric = {false};
  for (const BandResult& b : o.bands) {
    t.header.push_back(BandText(b.band.lo_hz, b.band.hi_hz));
    t.numeric.push_back(true);
  }
  t.header.push_back("whole grid");
  t.numeric.push_back(true);
  std::vector<std::size_t> largest(o.bands.size(), 0);
  for (std::size_t b = 0; b < o.bands.size(); ++b)
    for (std::size_t c = 0; c < o.contributors.size(); ++c)
      if (o.bands[b].contributor_variance[c] > o.bands[b].contributor_variance[largest[b]]) largest[b] = c;
  for (std::size_t c : ShareOrder(o)) {
    std::vector<std::string> row = {o.contributors[c].name};
    std::vector<bool> bold = {false};
    for (std::size_t b = 0; b < o.bands.size(); ++b) {
      row.push_back(Sig(std::sqrt(WithoutRounding(o.bands[b].contributor_variance[c], o.bands[b].variance)), digits));
      bold.push_back(largest[b] == c && o.bands[b].variance > 0.0);
    }
    row.push_back(Sig(std::sqrt(WithoutRounding(o.contributors[c].variance, o.variance)), digits));
    bold.push_back(false);
    t.rows.push_back(row);
    t.emphasis.push_back(bold);
  }
  std::vector<std::string> total = {"total"};
  for (const BandResult& b : o.bands) total.push_back(Sig(std::sqrt(b.variance), digits));
  total.push_back(Sig(o.rms(), digits));
  t.rows.push_back(total);
  return t;
}

Table ParametersTable(const BudgetOutline& outline, int digits) {
  Table t;
  t.title = "Parameters";
  t.header = {"parameter", "value", "unit", "formula", "description"};
  t.numeric = {false, true, false, false, false};
  bool plain = false;
  for (const ParameterOutline& p : outline.parameters) {
    plain = plain || p.unit.empty();
    t.rows.push_back({p.name, SignificantText(p.value, std::max(digits, 6)), p.unit.empty() ? "–" : UnitText(p.unit),
                      p.derived ? p.expression : "", p.description});
  }
  // A dimensionless parameter is a plain number in the units of the field
  // that takes it (a gain, a spectrum level: docs/budget_reference.md).
  if (plain) t.title += "; unit –: a plain number, in the units of the field that uses it";
  return t;
}

ReportFacts MakeFacts(const BudgetResult& result, const std::string& budget_file, const std::string& sha256,
                      const std::string& date, std::optional<double> seconds) {
  ReportFacts f;
  std::size_t failed = 0, required = 0;
  for (const OutputResult& o : result.outputs) {
    required += (o.rms_max ? 1 : 0) + o.band_requirements.size();
    failed += o.pass() ? 0 : 1;
    for (const BandRequirementResult& r : o.band_requirements) failed += r.pass() ? 0 : 1;
  }
  f.items = {
      {"budget", result.outline.name, true},
      {"budget file", budget_file.empty() ? "–" : budget_file},
      {"SHA-256", sha256.empty() ? "–" : sha256},
      {"date", date},
      {"deb version", DEB_VERSION, true},
      {"grid", ToString(result.outline.grid_kind) + ", " + std::to_string(result.grid.size()) + " frequencies, " +
                   HzText(result.grid.min_hz()) + "–" + HzText(result.grid.max_hz()) + " Hz"},
      {"bands", result.outline.bands.empty() ? "decades of the grid" : "as the budget defines them"},
      {"evaluation", seconds ? Sig(*seconds, 3) + " s"
                             : "not recorded: a reproducible report (the same bytes on every run) leaves the time out"},
      {"requirements", required == 0 ? "none given"
                                     : (failed == 0 ? "all " + std::to_string(required) + " met"
                                                    : std::to_string(failed) + " of " + std::to_string(required) +
                                                          " FAILED"),
       true},
  };
  // The nominal case of a swept or toleranced budget, which a reader may take for the study.
  if (const std::size_t n = result.outline.uncertain_parameters; n > 0)
    f.items.insert(f.items.begin() + 2,
                   {"tolerances", "not sampled: this report is the nominal design (deb uncertainty samples the " +
                                      std::to_string(n) + " uncertain parameter" + (n == 1 ? "" : "s") + ")",
                    false});
  if (result.outline.has_sweep)
    f.items.insert(f.items.begin() + 2, {"sweep",
                                         "not run: this report is the budget as written (deb sweep evaluates its "
                                         "variants)",
                                         false});
  f.conventions = {
      "Frequencies in Hz. PSDs are one-sided: variance = ∫ S(f) df over 0 < f < ∞, in unit²/Hz; ASD = √PSD.",
      "CPS(f) = ∫ S from the lowest grid frequency to f; RMS = √CPS(f_max); the reverse CPS integrates from f up.",
      "Contributors (source × path) are mutually uncorrelated and their variances add; S_y = H S_u Hᴴ.",
      "Exact RMS: Lyapunov A P + P Aᵀ + B W Bᵀ = 0, W = S₀/2, over 0 < f < ∞ (white sources only).",
      "A source declared two-sided (convention: two-sided) is converted once at load: S_one-sided = 2 S_two-sided.",
      "Share: a contributor's fraction of the output's variance (shares add to 100 %; RMS values do not add).",
  };
  // What the contributor tables' last column holds: k where an output meets
  // its limit, "must drop" where it fails (ContributorTable).
  bool allocation = false, must_drop = false;
  for (const OutputResult& o : result.outputs) {
    allocation = allocation || (o.rms_max && o.pass());
    must_drop = must_drop || (o.rms_max && !o.pass());
  }
  if (allocation)
    f.conventions.push_back("Allocation k = (rms_max² − (σ² − σ_c²)) / σ_c²: the factor on a contributor's source PSD "
                            "that puts the output at its limit, the others unchanged (k > 1: room to grow).");
  if (must_drop)
    f.conventions.push_back("Must drop (an output over its limit): the factor on a contributor's RMS that brings the "
                            "output to its limit, the others unchanged, or where none can alone, the factor on each "
                            "of the n largest together.");
  return f;
}

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

Table WithNotesBelow(const Table& table, std::vector<std::string>* notes, std::size_t min_characters) {
  const auto mark = [](std::size_t k) { return SuperscriptText(std::to_string(k)); };
  // Counted per column: a parameter named by its key path in two columns
  // of one row is a name, not a note.
  std::map<std::pair<std::size_t, std::string>, int> count;
  std::set<std::string> below;
  for (const auto& row : table.rows)
    for (std::size_t c = 0; c < row.size(); ++c)
      if (!(c < table.numeric.size() && table.numeric[c]) && Width(row[c]) >= min_characters) {
        const bool note_column = c < table.header.size() && table.header[c] == "note";
        if (++count[{c, row[c]}] > 1 || note_column) below.insert(row[c]);
      }
  Table out = table;
  std::map<std::string, std::string> mark_of;
  for (auto& row : out.rows)
    for (std::string& cell : row) {
      if (below.count(cell) == 0) continue;
      auto [it, added] = mark_of.emplace(cell, mark(mark_of.size() + 1));
      if (added) notes->push_back(it->second + " " + cell);
      cell = it->second;
    }
  return out;
}

std::string ToHtml(const Table& table) {
  std::vector<std::string> notes;
  const Table t = WithNotesBelow(table, &notes);
  notes.insert(notes.end(), table.notes.begin(), table.notes.end());
  std::string s = "<table>\n<caption>" + HtmlEscape(t.title) + "</caption>\n<thead><tr>";
  for (std::size_t c = 0; c < t.header.size(); ++c)
    s += std::string(t.numeric[c] ? "<th class=\"num\">" : "<th>") + HtmlEscape(t.header[c]) + "</th>";
  s += "</tr></thead>\n<tbody>\n";
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    s += "<tr>";
    for (std::size_t c = 0; c < t.rows[r].size(); ++c) {
      std::string cell = HtmlEscape(t.rows[r][c]);
      if (Emphasised(t, r, c)) cell = "<strong>" + cell + "</strong>";
      const bool fail = t.rows[r][c] == "FAIL";  // a status column: red in the page
      s += std::string("<td") + (t.numeric[c] ? (fail ? " class=\"num fail\"" : " class=\"num\"") : fail ? " class=\"fail\"" : "") +
           ">" + cell + "</td>";
    }
    s += "</tr>\n";
  }
  s += "</tbody>\n";
  if (!notes.empty()) {
    s += "<tfoot><tr><td class=\"notes\" colspan=\"" + std::to_string(t.header.size()) + "\">";
    for (std::size_t i = 0; i < notes.size(); ++i) s += (i ? "<br>" : "") + HtmlEscape(notes[i]);
    s += "</td></tr></tfoot>\n";
  }
  return s + "</table>\n";
}

std::string ToMarkdown(const Table& t) {
  // A table without a header (a study's sources) gets blank header cells:
  // Markdown has no table without one.
  const std::size_t columns = t.header.empty() ? t.numeric.size() : t.header.size();
  std::string s = "| ";
  for (std::size_t c = 0; c < columns; ++c) s += (t.header.empty() ? "" : MarkdownEscape(t.header[c])) + " | ";
  s.pop_back();
  s += "\n|";
  for (std::size_t c = 0; c < columns; ++c) s += t.numeric[c] ? " ---: |" : " --- |";
  s += "\n";
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    s += "| ";
    for (std::size_t c = 0; c < t.rows[r].size(); ++c) {
      const std::string cell = MarkdownEscape(t.rows[r][c]);
      s += (Emphasised(t, r, c) && !cell.empty() ? "**" + cell + "**" : cell) + " | ";
    }
    s.pop_back();
    s += "\n";
  }
  if (!t.notes.empty()) {
    s += "\n";
    for (const std::string& note : t.notes) s += MarkdownEscape(note) + "\n\n";
    s.pop_back();
  }
  return s;
}

std::vector<std::string> ToText(const Table& t, std::size_t max_cell, std::size_t max_line,
                                std::vector<std::string>* shortened) {
  std::vector<std::vector<std::string>> cells = {t.header};
  for (const auto& row : t.rows) cells.push_back(row);
  const std::vector<std::vector<std::string>> full = cells;
  const std::size_t columns = t.header.size();
  std::vector<std::size_t> width(columns, 0);
  for (auto& row : cells)
    for (std::size_t c = 0; c + 1 < columns && c < row.size(); ++c) {
      row[c] = Shorten(row[c], max_cell);
      width[c] = std::max(width[c], Width(row[c]));
    }
  std::size_t used = 0;
  for (std::size_t c = 0; c + 1 < columns; ++c) used += width[c] + 2;
  const std::size_t last = std::max<std::size_t>(max_line > used ? max_line - used : 0, 12);
  for (auto& row : cells)
    if (row.size() == columns) {
      row.back() = Shorten(row.back(), last);
      width.back() = std::max(width.back(), Width(row.back()));
    }
  if (shortened)
    for (std::size_t r = 1; r < cells.size(); ++r)
      for (std::size_t c = 0; c < cells[r].size(); ++c)
        if (cells[r][c] != full[r][c]) shortened->push_back(full[r][0] + ": " + t.header[c] + ": " + full[r][c]);
  std::vector<std::string> lines;
  for (std::size_t r = 0; r < cells.size(); ++r) {
    std::string line;
    for (std::size_t c = 0; c < cells[r].size(); ++c) {
      const std::string pad(width[c] - Width(cells[r][c]), ' ');
      line += (c ? "  " : "") + (t.numeric[c] ? pad + cells[r][c] : cells[r][c] + pad);
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    lines.push_back(line);
    if (r == 0) {
      std::size_t total = 0;
      for (std::size_t w : width) total += w;
      lines.push_back(std::string(total + 2 * (width.size() - 1), '-'));
    }
  }
  return lines;
}

}  // namespace deb::report
