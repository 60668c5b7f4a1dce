#include "deb/budget/loop_analysis.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <set>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {
namespace {

// Relative agreement of two loop gains that makes them one physical loop.
constexpr double kSameLoopTolerance = 1e-9;

bool SameValue(std::complex<double> a, std::complex<double> b) {
  return std::abs(a - b) <= kSameLoopTolerance * std::max(std::abs(a), std::abs(b));
}

// One-channel loops a and b (evaluated on the same frequencies f) with the
// same loop gain: first on every 64th frequency, then on all of them.
bool SameLoopGain(const FeedbackLoop& a, const FeedbackLoop& b, const std::vector<double>& f) {
  for (std::size_t step : {std::size_t{64}, std::size_t{1}})
    for (std::size_t i = 0; i < f.size(); i += step)
      if (!SameValue(a.LoopGainAt(f[i])(0, 0), b.LoopGainAt(f[i])(0, 0))) return false;
  return true;
}

// A part of a loop that is a constant gain (the 1 of "G K closed by 1").
bool StaticGain(const FrequencyModel& m) {
  if (m.HasData() || !m.IrrationalBlocks().empty() || !m.ModalParts().empty()) return false;
  for (const StateSpace& part : m.RationalParts())
    if (part.states() > 0) return false;
  return true;
}

// A form that names the physical plant and controller (neither a constant
// gain) is the one a loop is reported as.
bool NamesPhysicalParts(const FeedbackLoop& loop) {
  return !StaticGain(*loop.plant_model) && !StaticGain(*loop.controller_model);
}

// Merges each evaluated one-channel loop into an earlier one with the same
// loop gain on the same frequencies; the merged loop is reported in the
// form that names the physical plant and controller, where one does.
void MergeSameLoops(std::vector<LoopResult>& loops, std::vector<const FeedbackLoop*>& of,
                    std::vector<std::vector<double>>& f_of) {
  for (std::size_t j = 1; j < loops.size(); ++j) {
    if (!loops[j].evaluated || loops[j].margins.channels != 1) continue;
    for (std::size_t i = 0; i < j; ++i) {
      if (!loops[i].evaluated || loops[i].margins.channels != 1 || f_of[i] != f_of[j]) continue;
      if (!SameLoopGain(*of[i], *of[j], f_of[j])) continue;
      const bool swap = !NamesPhysicalParts(*of[i]) && NamesPhysicalParts(*of[j]);
      LoopResult merged = swap ? loops[j] : loops[i];
      // Every form in the order the paths show them, less the one reported.
      std::vector<LoopForm> forms = {{loops[i].plant, loops[i].controller, loops[i].sign}};
      forms.insert(forms.end(), loops[i].same_loop.begin(), loops[i].same_loop.end());
      forms.push_back({loops[j].plant, loops[j].controller, loops[j].sign});
      merged.same_loop.clear();
      for (const LoopForm& f : forms)
        if (!(f.plant == merged.plant && f.controller == merged.controller && f.sign == merged.sign))
          merged.same_loop.push_back(f);
      if (merged.required.empty()) merged.required = swap ? loops[i].required : loops[j].required;
      merged.paths = loops[i].paths;
      for (const std::string& p : loops[j].paths)
        if (std::find(merged.paths.begin(), merged.paths.end(), p) == merged.paths.end()) merged.paths.push_back(p);
      loops[i] = std::move(merged);
      if (swap) of[i] = of[j];
      loops.erase(loops.begin() + static_cast<std::ptrdiff_t>(j));
      of.erase(of.begin() + static_cast<std::ptrdiff_t>(j));
      f_of.erase(f_of.begin() + static_cast<std::ptrdiff_t>(j));
      --j;
      break;
    }
  }
}

}  // namespace

double MarginCheck::ratio() const {
  if (std::isnan(actual) || actual <= 0.0) return std::numeric_limits<double>::infinity();
  return std::isinf(actual) ? 0.0 : required / actual;
}

std::vector<MarginCheck> MarginChecks(const LoopResult& loop) {
  std::vector<MarginCheck> out;
  const MarginRequirement& q = loop.required;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const LoopMargins& m = loop.margins;
  if (q.gain_db) {
    double actual = nan;
    if (loop.evaluated && m.channels == 1)
      actual = m.upper_gain_margin ? 20.0 * std::log10(m.upper_gain_margin->gain_margin) : inf;
    out.push_back({"gain margin", "dB", *q.gain_db, actual});
  }
  if (q.phase_deg) {
    double actual = nan;
    if (loop.evaluated && m.channels == 1) actual = m.phase_margin ? m.phase_margin->phase_margin_deg : inf;
    out.push_back({"phase margin", "deg", *q.phase_deg, actual});
  }
  if (q.modulus) out.push_back({"modulus margin", "", *q.modulus, loop.evaluated ? m.modulus_margin : nan});
  return out;
}

std::string MarginChecksText(const LoopResult& loop) {
  std::string text;
  for (const MarginCheck& c : MarginChecks(loop)) {
    const std::string unit = c.unit.empty() ? "" : " " + c.unit;
    const std::string actual = std::isnan(c.actual) ? "not evaluated"
                               : std::isinf(c.actual) ? "infinite"
                                                      : SignificantText(c.actual, 4) + unit;
    text += (text.empty() ? "" : "; ") + c.what + " " + actual + " >= " + SignificantText(c.required, 4) + unit + ": " +
            (c.pass() ? "PASS" : "FAIL");
  }
  return text;
}

std::vector<LoopResult> AnalyseLoops(const Budget& budget, const std::vector<double>& f_hz) {
  std::vector<LoopResult> loops;
  std::vector<const FeedbackLoop*> of;  // the FeedbackLoop behind each result
  std::set<std::string> seen_paths;
  for (const Contributor& c : budget.contributors) {
    if (!seen_paths.insert(c.path).second) continue;
    const Path& path = budget.FindPath(c.path);
    for (const FeedbackLoop& loop : path.loops) {
      auto same = std::find_if(loops.begin(), loops.end(), [&](const LoopResult& r) {
        return r.plant == loop.plant && r.controller == loop.controller && r.sign == loop.sign;
      });
      if (same == loops.end()) {
        LoopResult r;
        r.plant = loop.plant;
        r.controller = loop.controller;
        r.sign = loop.sign;
        loops.push_back(std::move(r));
        of.push_back(&loop);
        same = loops.end() - 1;
      }
      if (std::find(same->paths.begin(), same->paths.end(), path.name) == same->paths.end())
        same->paths.push_back(path.name);
      if (same->required.empty()) same->required = loop.required;
    }
  }
  std::vector<std::vector<double>> f_of(loops.size());  // the frequencies each loop is evaluated on
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const FeedbackLoop& loop = *of[i];
    std::vector<double>& f = f_of[i];
    const auto g = loop.plant_model->DefinedRangeHz(), k = loop.controller_model->DefinedRangeHz();
    for (double x : f_hz)
      if ((!g || g->Contains(x, x)) && (!k || k->Contains(x, x))) f.push_back(x);
    if (f.size() < 2) {
      loops[i].note = "fewer than 2 grid frequencies lie where the loop's measured data are defined";
      continue;
    }
    try {
      const auto finite = [](const Eigen::MatrixXcd& l, double x) {
        if (!l.allFinite()) throw InputError("the loop gain is not finite at " + std::to_string(x) + " Hz");
      };
      std::vector<Eigen::MatrixXcd> on_grid = loop.LoopGains(f);
      for (std::size_t k = 0; k < f.size(); ++k) finite(on_grid[k], f[k]);
      loops[i].margins = ComputeLoopMargins(
          [&](double x) {
            Eigen::MatrixXcd l = loop.LoopGainAt(x);
            finite(l, x);
            return l;
          },
          f, std::move(on_grid));
      loops[i].evaluated = true;
      const LoopMargins& m = loops[i].margins;
      const double at_hz = m.phase_margin ? m.phase_margin->f_hz : m.modulus_margin_f_hz;
      for (const FrequencyModel* part : {loop.plant_model.get(), loop.controller_model.get()})
        for (const IrrationalBlock& b : part->IrrationalBlocks()) {
          const ApproximationError e = ApproximationErrorAt(b, at_hz);
          loops[i].approximations.push_back({b.Describe(), b.DescribeApproximation(), at_hz, e.phase_deg, e.gain_ratio});
        }
    } catch (const InputError& e) {
      loops[i].note = e.message();
    }
  }
  MergeSameLoops(loops, of, f_of);
  return loops;
}

std::string SameLoopText(const LoopResult& loop) {
  std::string text;
  for (const LoopForm& f : loop.same_loop)
    text += (text.empty() ? "" : ", ") + f.plant + " closed by " + f.controller +
            (f.sign == loop.sign ? "" : f.sign < 0 ? " (negative feedback)" : " (positive feedback)");
  return text;
}

std::string MarginsText(const LoopResult& loop) {
  if (!loop.evaluated) return "no margins: " + loop.note;
  const LoopMargins& m = loop.margins;
  const auto at = [](double f_hz) { return " at " + SignificantText(f_hz) + " Hz"; };
  std::string text;
  if (m.channels == 1) {
    text = m.phase_margin ? "phase margin " + SignificantText(m.phase_margin->phase_margin_deg) + " deg" +
                                at(m.phase_margin->f_hz)
                          : "no gain crossover (|L| = 1) on the grid";
    if (m.upper_gain_margin)
      text += ", gain margin " + SignificantText(m.upper_gain_margin->gain_margin) + " (" +
              SignificantText(ToDecibel(m.upper_gain_margin->gain_margin)) + " dB)" + at(m.upper_gain_margin->f_hz);
    if (m.lower_gain_margin)
      text += ", lower gain margin " + SignificantText(m.lower_gain_margin->gain_margin) + " (" +
              SignificantText(ToDecibel(m.lower_gain_margin->gain_margin)) + " dB)" + at(m.lower_gain_margin->f_hz);
    if (!m.upper_gain_margin && !m.lower_gain_margin) text += ", no phase crossover on the grid";
    text += ", ";
  } else {
    text = std::to_string(m.channels) + " channels: ";
  }
  text += "modulus margin " + SignificantText(m.modulus_margin) + at(m.modulus_margin_f_hz);
  for (const LoopApproximation& a : loop.approximations)
    text += "; " + a.block + " by " + a.approximation + ": phase error " + SignificantText(a.phase_error_deg) +
            " deg, gain ratio " + SignificantText(a.gain_ratio, 8) + at(a.f_hz);
  return text;
}

}  // namespace deb
