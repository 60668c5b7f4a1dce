#include "deb/budget/engine.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "deb/budget/engine_steps.h"
#include "deb/budget/path_composition.h"
#include "deb/budget/path_response.h"
#include "deb/budget/response_traces.h"
#include "deb/core/error.h"
#include "deb/core/integrate.h"
#include "deb/core/number_text.h"
#include "deb/spectra/tone_spectrum.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/modes.h"
#include "deb/units/unit.h"

namespace deb {
namespace evaluation {

// Keeps the first of each repeated warning (a path shared by several contributors warns once).
void Deduplicate(std::vector<std::string>* warnings) {
  std::vector<std::string> unique;
  for (std::string& w : *warnings)
    if (std::find(unique.begin(), unique.end(), w) == unique.end()) unique.push_back(std::move(w));
  *warnings = std::move(unique);
}

BudgetResult EvaluateUnlocated(const Budget& budget, const EngineOptions& options) {
  FullPlan full = MakePlan(budget);
  EvaluationPlan& plan = full.plan;
  BudgetResult result;
  result.outline = OutlineOf(budget);
  result.paths = std::move(plan.paths);
  result.grid = std::move(plan.grid);
  result.warnings = std::move(plan.warnings);
  result.loops = std::move(plan.loops);
  const std::vector<double>& f = result.grid.f_hz();

  // Weighting responses, shared by all contributors of an output.
  std::vector<std::vector<double>> weighting_gain2(budget.outputs.size());
  for (std::size_t o = 0; o < budget.outputs.size(); ++o)
    weighting_gain2[o] = WeightingGain2(budget.outputs[o], f, options.threads);

  result.outputs.resize(budget.outputs.size());
  for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
    OutputResult& r = result.outputs[o];
    r.name = budget.outputs[o].name;
    r.signal = budget.outputs[o].signal;
    r.unit = budget.outputs[o].unit;
    r.rms_max = budget.outputs[o].rms_max;
    r.metric = budget.outputs[o].metric;
  }

  // Each contributor's path responses, from its propagation (response traces).
  std::vector<std::vector<PathResponse>> recorded(budget.contributors.size());
  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    const Source& source = budget.FindSource(c.source);
    const PathAnalysis& analysis = *result.paths.at(ContributorPathKey(c));
    const Path& path = analysis.path();
    const ContributorSetup& setup = full.setups[ci];
    const bool breakdown = c.breakdown_channels && options.channel_breakdown;
    const OutputFactor output_factor{setup.out_conv, weighting_gain2, f};
    const InputSpectrum input(*source.spectrum, setup.in_conv);
    std::vector<std::vector<std::vector<double>>> channel_psd;
    std::optional<PathResponseRecorder> recorder;
    if (options.response_traces) recorder.emplace(budget, analysis, ci, f, options.threads);
    std::vector<std::vector<double>> psd =
        Propagate(budget, ci, analysis, input, setup, f, output_factor, options.threads,
                  breakdown ? &channel_psd : nullptr, recorder ? &*recorder : nullptr);
    if (recorder) recorded[ci] = recorder->Take();
    const std::vector<std::vector<ContributorResult::Tone>> tones =
        PropagateTones(budget, ci, analysis, source.spectrum->Lines(), setup);
    const bool purely_tonal = IsPurelyTonal(source);

    std::vector<std::size_t> split;  // outputs whose modes are split on the grid
    for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
      ContributorResult cr;
      cr.name = c.name;
      cr.source = c.source;
      cr.path = c.path;
      cr.inputs = c.inputs;
      cr.group = c.group;
      cr.psd = std::move(psd[o]);
      cr.cps = CumulativeIntegral(result.grid, cr.psd);
      cr.tail_variance_estimate = TailEstimate(f, cr.psd);
      if (!tones.empty()) {
        cr.tones = tones[o];
        double tonal = 0.0;
        for (const ContributorResult::Tone& t : cr.tones) {
          tonal += t.variance;
          AddToneStep(f, t.f_hz, t.variance, &cr.cps);
        }
        if (purely_tonal) cr.exact_variance = tonal;  // |H(f0) a|^2 is the exact variance of a sinusoid
      }
      cr.variance = cr.cps.back();
      if (breakdown)
        BreakDownChannels(source, result.grid, channel_psd[o], ChannelTones(analysis, source.spectrum->Lines(), setup, o),
                          &cr);
      if (!purely_tonal)
        AddExactVariance(budget, ci, o, analysis, setup, plan.exact_refusal[ci][o], options, &cr, &result.warnings);
      result.outputs[o].contributors.push_back(std::move(cr));
      if (analysis.modal() && result.outputs[o].contributors.back().top_modes.empty()) split.push_back(o);
    }
    if (!split.empty())
      SplitGridVarianceByMode(path, analysis, input, setup, result.grid, output_factor, split, options.threads,
                              &result.outputs);
  }
  Deduplicate(&result.warnings);
  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    AddTotalsAndBands(budget.outputs[o], result.grid, plan.bands, &result.outputs[o]);
    try {
      AddReferences(budget.outputs[o], o, result.grid, weighting_gain2[o], &result.outputs[o]);
    } catch (const InputError& e) {
      if (!e.key_path().empty()) throw;
      throw InputError(Key("outputs", o, "references"), e.message());
    }
  }
  // The traces first: the covariance reads the paths' responses from them.
  if (options.response_traces)
    result.traces = std::make_shared<const ResponseTraces>(ComputeResponseTraces(budget, result, std::move(recorded)));
  if (options.covariance && !budget.covariance.empty())
    result.covariance = ComputeOutputCovariance(budget, result, options.threads);
  return result;
}

}  // namespace evaluation

using namespace evaluation;

bool EngineOptions::IsValid(std::string* error) const {
  if (std::isfinite(exact_tolerance) && exact_tolerance > 0.0) return true;
  if (error) *error = "engine options: exact_tolerance " + SignificantText(exact_tolerance) + " must be finite and > 0";
  return false;
}

BudgetResult Evaluate(const Budget& budget, const EngineOptions& options) {
  if (std::string why; !options.IsValid(&why)) throw InputError(why);
  try {
    return EvaluateUnlocated(budget, options);
  } catch (const InputError& e) {
    throw budget.Locate(e);  // at file:line:col, from the positions recorded at load
  }
}

}  // namespace deb
