#include "deb/budget/budget_description.h"

#include <algorithm>
#include <vector>

#include "deb/budget/budget_outline.h"
#include "deb/budget/loop_analysis.h"
#include "deb/budget/path_analysis.h"
#include "deb/core/formatted_text.h"
#include "deb/systems/axis_cancellation.h"
#include "deb/systems/modes.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

// "stable", "unstable: ...", or marginally stable with what sits on the
// axis: a controller's integrator is not a fault, but it has no exact
// variance on its own and a loop must close around it. Axis poles the
// transfer cancels (axis_cancellation.h) are named as such.
std::string Stability(const StateSpace& system, const PathAnalysis* analysis) {
  // The analysis has the poles already (of the evaluated rows' realisation:
  // the same A); computing them again cost 7 s at 2000 states.
  const PoleStability s = ClassifyPoles(analysis ? analysis->StateSpacePoles() : system.Poles());
  if (!s.unstable.empty()) return "unstable: no contributor may use it";
  if (s.marginal.empty()) return "stable";
  const auto at_origin = [](const std::vector<std::complex<double>>& poles) {
    return std::all_of(poles.begin(), poles.end(), [](const std::complex<double>& z) { return std::abs(z) <= 1e-9; });
  };
  const std::string count = std::to_string(s.marginal.size());
  if (CancelAxisPoles(system))
    return at_origin(s.marginal) ? "stable (" + count + " pole(s) at 0 cancelled by zeros at 0: they do not reach the outputs)"
                                 : "stable (" + count + " pole(s) on the imaginary axis cancelled by zeros there: they do not reach the outputs)";
  return at_origin(s.marginal) ? "marginally stable (integrator: " + count + " pole(s) at 0; close a loop around it)"
                               : "marginally stable (" + count + " pole(s) on the imaginary axis)";
}

void AddPath(std::string& text, const Path& p, const EvaluationPlan& plan) {
  if (p.HasMeasuredData()) {
    const std::vector<double> f = p.measured->DataFrequencies();
    AppendFormatted(text, "  %-20s %d input(s) -> %d output(s), measured frequency data (%zu points, %g-%g Hz)%s\n",
                    p.name.c_str(), p.system.inputs(), p.system.outputs(), f.size(), f.front(), f.back(),
                    p.measured->HasLoopAroundData() ? ", loop stability not verified" : "");
    return;
  }
  if (p.IsModal()) {
    const ModalModel& m = *p.modal;
    const auto [lo, hi] = std::minmax_element(m.f_hz.begin(), m.f_hz.end());
    AppendFormatted(text, "  %-20s %d input(s) -> %d output(s), %d mode(s), %g-%g Hz, %s\n", p.name.c_str(),
                    p.system.inputs(), p.system.outputs(), m.modes(), *lo, *hi,
                    *lo > 0.0 ? "stable" : "rigid-body mode(s) at 0 Hz");
    for (const std::string& note : m.notes) AppendFormatted(text, "  %-20s %s\n", "", note.c_str());
    return;
  }
  std::string approximated;
  if (p.SystemApproximates())
    for (const IrrationalBlock& b : p.measured->IrrationalBlocks())
      approximated += (approximated.empty() ? " (exact on the grid; poles and variance by its approximation: "
                                            : "; ") + b.Describe() + " by " + b.DescribeApproximation();
  if (!approximated.empty()) approximated += ")";
  // The analysis of a contributor's use of the path as a state space, if any.
  const PathAnalysis* analysis = nullptr;
  for (const auto& [key, a] : plan.paths)
    if (a && a->path().name == p.name && !a->ResponseForm().empty()) {  // a state space, evaluated as one
      analysis = a.get();
      break;
    }
  // A diagram kept as parts has its poles from a contributor's analysis only.
  const std::string stability = p.KeptAsParts() && !analysis ? "poles not computed (no contributor uses it)"
                                                             : Stability(p.system, analysis);
  AppendFormatted(text, "  %-20s %d input(s) -> %d output(s), %d state(s)%s, %s\n", p.name.c_str(), p.system.inputs(),
                  p.system.outputs(), p.States(), approximated.c_str(), stability.c_str());
  // How its H is evaluated.
  if (analysis)
    AppendFormatted(text, "  %-20s H by %s\n", "", analysis->ResponseForm().c_str());
}

// A spectrum's description (in "unit^2/Hz", as a spectrum knows no unit) in
// its source's unit: "N^2/Hz", "(m/s)^2/Hz".
std::string InSourceUnit(std::string described, const std::string& unit) {
  const std::string token = "unit^2/Hz";
  const std::string psd = PsdUnitLabel(unit);
  for (std::size_t at = described.find(token); at != std::string::npos; at = described.find(token, at + psd.size()))
    described.replace(at, token.size(), psd);
  return described;
}

void AddContributors(std::string& text, const Budget& budget, const EvaluationPlan& plan) {
  AppendFormatted(text, "contributors:\n");
  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    AppendFormatted(text, "  %-20s source %s, path %s, exact variance: %s\n", c.name.c_str(), c.source.c_str(),
                    ContributorPathKey(c).c_str(), ToString(c.exact).c_str());
    // Why there will be none where it was asked for, once per distinct reason (the outputs usually share
    // it), naming the outputs unless it holds for every one.
    std::vector<std::pair<std::string, std::vector<std::string>>> reasons;  // why, for which outputs
    const std::vector<std::string>& refusals = plan.exact_refusal[ci];
    for (std::size_t o = 0; o < refusals.size(); ++o) {
      const std::string& why = refusals[o];
      if (c.exact == ExactVariance::kOff || why.empty()) continue;
      auto it = std::find_if(reasons.begin(), reasons.end(), [&](const auto& r) { return r.first == why; });
      if (it == reasons.end()) it = reasons.insert(reasons.end(), {why, {}});
      if (o < budget.outputs.size()) it->second.push_back(budget.outputs[o].name);
    }
    for (const auto& [why, outputs] : reasons) {
      std::string where;
      if (outputs.size() < refusals.size())
        for (const std::string& o : outputs) where += (where.empty() ? " for " : ", ") + o;
      AppendFormatted(text, "  %-20s no exact variance%s: %s\n", "", where.c_str(), why.c_str());
    }
  }
}

void AddOutputs(std::string& text, const Budget& budget) {
  AppendFormatted(text, "outputs:\n");
  for (const auto& o : budget.outputs) {
    AppendFormatted(text, "  %-20s signal %s in %s", o.name.c_str(), o.signal.c_str(), o.unit.c_str());
    if (o.weighting) AppendFormatted(text, ", weighted (%s)", o.weighting->unit.c_str());
    if (o.metric) AppendFormatted(text, ", %s", o.metric->Describe().c_str());
    if (o.rms_max) AppendFormatted(text, ", rms_max %g", *o.rms_max);
    AppendFormatted(text, "\n");
  }
  if (!budget.covariance.empty()) {  // validated with the budget: outputs that exist, once each, without a metric
    std::string names;
    for (const std::string& name : budget.covariance) names += (names.empty() ? "" : ", ") + name;
    AppendFormatted(text, "covariance of %zu outputs: %s (deb run: summary.json and the reports)\n",
                    budget.covariance.size(), names.c_str());
  }
}

}  // namespace

std::string DescribeBudget(const Budget& budget, const EvaluationPlan& plan) {
  std::string text;
  const FrequencyGrid& grid = plan.grid;
  AppendFormatted(text, "budget %s: valid\n", budget.name.c_str());
  if (!budget.description.empty()) AppendFormatted(text, "  %s\n", budget.description.c_str());
  AppendFormatted(text, "grid: %s, %zu frequencies, %g-%g Hz\n", ToString(budget.grid.kind).c_str(), grid.size(),
                  grid.min_hz(), grid.max_hz());
  if (!budget.parameters.empty()) {
    AppendFormatted(text, "parameters:\n");
    for (const ParameterOutline& p : OutlineOf(budget.parameters))
      AppendFormatted(text, "  %-20s %.6g%s%s%s\n", p.name.c_str(), p.value, p.unit.empty() ? "" : " ",
                      p.unit.c_str(), p.derived ? ("  = " + p.expression).c_str() : "");
  }
  AppendFormatted(text, "sources:\n");
  for (const auto& s : budget.sources)
    AppendFormatted(text, "  %-20s %d channel(s) in %s: %s\n", s.name.c_str(), s.channels(), s.unit.c_str(),
                    InSourceUnit(s.spectrum->Describe(), s.unit).c_str());
  AppendFormatted(text, "paths:\n");
  for (const Path& p : budget.paths) AddPath(text, p, plan);
  if (!plan.loops.empty()) AppendFormatted(text, "feedback loops:\n");
  for (const LoopResult& loop : plan.loops) {
    std::string paths;
    for (const std::string& p : loop.paths) paths += (paths.empty() ? "" : ", ") + p;
    AppendFormatted(text, "  %s closed by %s (%s feedback), in %s\n", loop.plant.c_str(), loop.controller.c_str(),
                    loop.sign < 0 ? "negative" : "positive", paths.c_str());
    if (const std::string same = SameLoopText(loop); !same.empty())
      AppendFormatted(text, "    the same loop as %s\n", same.c_str());
    AppendFormatted(text, "    %s\n", MarginsText(loop).c_str());
    if (const std::string checks = MarginChecksText(loop); !checks.empty())
      AppendFormatted(text, "    required: %s\n", checks.c_str());
  }
  AddContributors(text, budget, plan);
  AddOutputs(text, budget);
  return text;
}

std::string DescribeSweep(const SweepSpec& spec, std::size_t variant_count) {
  std::string text;
  AppendFormatted(text, "sweep: %s of %zu parameter(s), %zu variants, each valid:\n", ToString(spec.mode).c_str(),
                  spec.parameters.size(), variant_count);
  for (const SweepParameter& p : spec.parameters) {
    AppendFormatted(text, "  %-40s %zu value(s): %s", p.key_path.c_str(), p.values.size(),
                    p.Text(p.values.front()).c_str());
    if (p.values.size() > 1) AppendFormatted(text, " ... %s", p.Text(p.values.back()).c_str());
    if (!p.label.empty() || !p.unit.empty()) AppendFormatted(text, " (%s)", p.AxisTitle().c_str());
    AppendFormatted(text, "\n");
  }
  return text;
}

}  // namespace deb
