#include "deb/budget/engine_steps.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

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

// The modes with the largest |part|, largest first: share = part / whole,
// variance = share x `variance` (the figure the parts split).
std::vector<ModeShare> TopModes(const ModalModel& model, const Eigen::VectorXd& part, double whole, double variance) {
  std::vector<int> order(static_cast<std::size_t>(part.size()));
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  const std::size_t top = std::min(order.size(), ContributorResult::kTopModes);
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(top), order.end(), [&](int a, int b) {
    return std::abs(part(a)) > std::abs(part(b)) || (std::abs(part(a)) == std::abs(part(b)) && a < b);
  });
  std::vector<ModeShare> shares;
  for (std::size_t i = 0; i < top; ++i) {
    const int k = order[i];
    ModeShare s;
    s.mode = k + 1;
    s.f_hz = model.f_hz[k];
    s.zeta = model.zeta[k];
    s.share = whole > 0.0 ? part(k) / whole : 0.0;
    s.variance = s.share * variance;
    shares.push_back(s);
  }
  return shares;
}

InputError RequiredExactError(std::size_t ci, const Contributor& c, const Output& out, const std::string& why) {
  return InputError(Key("contributors", ci, "exact"), "exact variance of contributor '" + c.name + "' on output '" +
                                                          out.name + "' is required but cannot be computed: " + why);
}

// A source of tones only (no density): its contributors' variance is exact.
bool IsPurelyTonal(const Source& source) {
  return dynamic_cast<const ToneSpectrum*>(source.spectrum.get()) != nullptr;
}

// Why contributor c gets no exact variance on output o; "" when one is attempted
// (white source, pure unit scales, a stable rational path, a rational weighting).
std::string ExactRefusal(const Contributor& c, const Source& source, const Path& path, const PathAnalysis& analysis,
                         const Output& out, const ContributorSetup& setup, std::size_t o) {
  if (c.exact == ExactVariance::kOff) return "not requested";
  if (path.HasMeasuredData())
    return "the path holds measured frequency data (no state-space model for a Lyapunov solution)";
  if (IsPurelyTonal(source)) return "";  // exact by construction: |H(f0) a|^2
  if (!source.spectrum->WhiteLevel())
    return "the source is not white (exact variance needs a flat spectrum without band limits)";
  if (!setup.inputs_pure_scale || !setup.out_conv[o].IsPureScale())
    return "the units differ by a time derivative (a factor j 2 pi f, improper: no state-space form)";
  if (!analysis.marginal_poles().empty()) return "the path has poles on the imaginary axis";
  if (out.metric)
    return "the " + ToString(out.metric->type) + " weighting " + out.metric->WeightingText() +
           " is not rational in s: no Lyapunov form";
  return "";
}

// The exact variance of contributor ci on output o into cr (or the reason
// there is none), and a warning where it disagrees with the grid's figure.
void AddExactVariance(const Budget& budget, std::size_t ci, std::size_t o, const PathAnalysis& analysis,
                      const ContributorSetup& setup, std::string refusal, const EngineOptions& options,
                      ContributorResult* cr, std::vector<std::string>* warnings) {
  const Contributor& c = budget.contributors[ci];
  const Path& path = analysis.path();
  const Output& out = budget.outputs[o];
  if (refusal.empty()) {
    const Eigen::MatrixXd w_two_sided = WhiteInputIntensity(budget.FindSource(c.source), setup.in_conv);
    try {
      const PathAnalysis::ExactVariance exact = analysis.Exact(path.OutputIndex(out.signal), w_two_sided,
                                                               out.weighting ? &out.weighting->system : nullptr);
      const double scale2 = setup.out_conv[o].scale * setup.out_conv[o].scale;
      cr->exact_variance = exact.variance * scale2;
      if (exact.mode_share.size() > 0) {
        cr->top_modes = TopModes(*path.modal, exact.mode_share, exact.variance, *cr->exact_variance);
        cr->top_modes_of = ModeSplit::kExactVariance;
      }
    } catch (const InputError& e) {
      refusal = e.what();
    }
  }
  if (!cr->exact_variance) {
    cr->exact_note = refusal;
    if (c.exact == ExactVariance::kRequired) throw RequiredExactError(ci, c, out, refusal);
    return;
  }
  if (!(*cr->exact_variance > 0.0)) return;
  // With tails that do not converge as power laws (no estimate), the grid
  // figure alone is compared.
  const bool tails = std::isfinite(cr->tail_variance_estimate);
  const double beyond = tails ? cr->tail_variance_estimate : 0.0;
  const double rel = std::abs(*cr->exact_variance - (cr->variance + beyond)) / *cr->exact_variance;
  if (rel > options.exact_tolerance) {
    std::ostringstream os;
    os << "contributor '" << c.name << "' on output '" << out.name << "': exact variance " << *cr->exact_variance
       << " and grid variance " << cr->variance;
    if (tails) os << " (+ " << beyond << " estimated beyond the grid)";
    else os << " (no estimate beyond the grid: its ends are not power-law tails)";
    os << " differ by " << rel << " relative; refine the grid or widen its range";
    warnings->push_back(os.str());
  }
}

// A modal path without the closed-form split (a source that is not white, a
// weighting, a derivative unit): the split of the grid integral, on the same
// grid and with the same factors as the PSD, for the outputs in `split`.
void SplitGridVarianceByMode(const Path& path, const PathAnalysis& analysis, const InputSpectrum& input,
                             const ContributorSetup& setup, const FrequencyGrid& grid,
                             const OutputFactor& output_factor, const std::vector<std::size_t>& split,
                             int threads, std::vector<OutputResult>* outputs) {
  const std::vector<double>& f = grid.f_hz();
  const std::size_t n = f.size();
  const std::vector<double> q = LinearQuadratureWeights(grid);
  std::vector<int> positions;
  std::vector<std::vector<double>> weight;
  for (const std::size_t o : split) {
    positions.push_back(setup.row_of_output[o]);
    std::vector<double> w(n);
    for (std::size_t k = 0; k < n; ++k) w[k] = output_factor(o, k);
    weight.push_back(std::move(w));
  }
  const Eigen::MatrixXd parts = analysis.ModeParts(
      f, q, positions, weight,
      [&input](double f_hz, Eigen::MatrixXcd& scratch) -> const Eigen::MatrixXcd& { return input.Full(f_hz, scratch); },
      threads);
  for (std::size_t i = 0; i < split.size(); ++i) {
    ContributorResult& cr = (*outputs)[split[i]].contributors.back();
    double whole = 0.0;  // the PSD's integral by the same linear rule
    for (std::size_t k = 0; k < n; ++k) whole += q[k] * cr.psd[k];
    cr.top_modes = TopModes(*path.modal, parts.col(static_cast<Eigen::Index>(i)), whole, cr.variance);
    cr.top_modes_of = ModeSplit::kGridVariance;
  }
}

}  // namespace evaluation

}  // namespace deb
