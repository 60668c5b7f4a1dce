#include "deb/budget/loop_analysis.h"

#include <algorithm>
#include <set>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {

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
    }
  }
  for (std::size_t i = 0; i < loops.size(); ++i) {
    const FeedbackLoop& loop = *of[i];
    std::vector<double> f;
    const auto g = loop.plant_model->DefinedRangeHz(), k = loop.controller_model->DefinedRangeHz();
    for (double x : f_hz)
      if ((!g || g->Contains(x, x)) && (!k || k->Contains(x, x))) f.push_back(x);
    if (f.size() < 2) {
      loops[i].note = "fewer than 2 grid frequencies lie where the loop's measured data are defined";
      continue;
    }
    try {
      loops[i].margins = ComputeLoopMargins(
          [&](double x) {
            Eigen::MatrixXcd l = loop.LoopGainAt(x);
            if (!l.allFinite()) throw InputError("the loop gain is not finite at " + std::to_string(x) + " Hz");
            return l;
          },
          f);
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
  return loops;
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
