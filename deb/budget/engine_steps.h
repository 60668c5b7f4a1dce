// Internal: not part of the public API.
// The steps of deb::Evaluate (engine.h), in three files by what they do:
//   engine_plan.cpp         the plan: path analyses, the grid, the checks of
//                           coverage and bands, each contributor's unit
//                           conversions and why it gets no exact variance
//   engine_propagation.cpp  S_y = H S_u H^H on the grid, tones, channel
//                           parts, totals, bands and references
//   engine_exact.cpp        the exact (Lyapunov) variance and the split of a
//                           modal path's variance by mode
// engine.cpp runs them in order. Shared here: the types they pass each other.
#pragma once

#include <Eigen/Dense>

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/engine.h"
#include "deb/budget/path_analysis.h"
#include "deb/budget/path_response.h"
#include "deb/budget/result.h"
#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/spectra/spectrum.h"
#include "deb/units/unit.h"

namespace deb::evaluation {

// The position of the item named `name` in the budget's sources or paths (Budget::Validate: it exists).
template <typename Item>
std::size_t IndexOf(const std::vector<Item>& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return i;
  DEB_DEMAND(false);
  return 0;
}

// S_u of a source as the path's inputs see it, F S_u F^H with F = diag of the
// input unit factors. A white source in pure-scale units gives the same
// matrix at every frequency, formed once; otherwise the spectrum is evaluated
// (and allocates) per frequency.
class InputSpectrum {
 public:
  InputSpectrum(const Spectrum& spectrum, const std::vector<UnitConversion>& conv)
      : spectrum_(spectrum), conv_(conv), diagonal_(spectrum.IsDiagonal()), pure_scale_(true) {
    for (const UnitConversion& u : conv) pure_scale_ &= u.IsPureScale();
    const auto white = spectrum.WhiteLevel();
    if (!white || !pure_scale_) return;
    constant_ = true;
    Eigen::MatrixXd level = *white;
    for (Eigen::Index i = 0; i < level.rows(); ++i)
      for (Eigen::Index j = 0; j < level.cols(); ++j) level(i, j) *= conv[i].scale * conv[j].scale;
    diag_ = level.diagonal();
    full_ = level.cast<std::complex<double>>();
  }

  bool diagonal() const { return diagonal_; }

  // The diagonal at f_hz (for a diagonal source); `scratch` holds it unless constant.
  const Eigen::VectorXd& Diagonal(double f_hz, Eigen::VectorXd& scratch) const {
    if (constant_) return diag_;
    scratch = spectrum_.Psd(f_hz);
    for (Eigen::Index j = 0; j < scratch.size(); ++j) scratch(j) *= conv_[j].PsdFactor(f_hz);
    return scratch;
  }

  // The full matrix at f_hz; `scratch` holds it unless constant.
  const Eigen::MatrixXcd& Full(double f_hz, Eigen::MatrixXcd& scratch) const {
    if (constant_) return full_;
    scratch = spectrum_.Csd(f_hz);
    const Eigen::Index m = scratch.rows();
    if (pure_scale_) {  // real factors: no complex products
      for (Eigen::Index j = 0; j < m; ++j)
        for (Eigen::Index i = 0; i < m; ++i) scratch(i, j) *= conv_[i].scale * conv_[j].scale;
      return scratch;
    }
    Eigen::VectorXcd factor(m);
    for (Eigen::Index j = 0; j < m; ++j) factor(j) = conv_[j].ResponseFactor(f_hz);
    for (Eigen::Index j = 0; j < m; ++j)
      for (Eigen::Index i = 0; i < m; ++i) scratch(i, j) *= factor(i) * std::conj(factor(j));
    return scratch;
  }

 private:
  const Spectrum& spectrum_;
  const std::vector<UnitConversion>& conv_;
  bool diagonal_;
  bool pure_scale_;  // every input conversion is a scale (no time derivative)
  bool constant_ = false;
  Eigen::VectorXd diag_;
  Eigen::MatrixXcd full_;
};

// The unit conversions and output rows of one contributor.
struct ContributorSetup {
  std::vector<UnitConversion> in_conv;  // per path input
  bool inputs_pure_scale = true;
  std::vector<int> row_of_output;          // per budget output: its position in the analysis
  std::vector<UnitConversion> out_conv;  // per budget output
};

// The factor on output o's PSD at f[k]: its unit conversion and weighting
// (called per frequency and output in the propagation: no type erasure).
struct OutputFactor {
  const std::vector<UnitConversion>& out_conv;               // per output
  const std::vector<std::vector<double>>& weighting_gain2;  // per output: per frequency, or empty
  const std::vector<double>& f_hz;

  double operator()(std::size_t o, std::size_t k) const {
    const UnitConversion& u = out_conv[o];
    double factor = u.IsPureScale() ? u.scale * u.scale : u.PsdFactor(f_hz[k]);  // no pow() when not needed
    if (!weighting_gain2[o].empty()) factor *= weighting_gain2[o][k];
    return factor;
  }
};

// The plan, and the unit conversions and rows of every contributor it
// worked out, which Evaluate reuses.
struct FullPlan {
  EvaluationPlan plan;
  std::vector<ContributorSetup> setups;  // per contributor
};

// "list[i]" or "list[i].field": a key path of the budget file.
std::string Key(const char* list, std::size_t i, const std::string& field = "");

// Variance of a power law continued beyond the grid ends through the first and
// last two points; infinite where the power law does not converge.
double TailEstimate(const std::vector<double>& f, const std::vector<double>& s);

// Keeps the first of each repeated warning (a path shared by several contributors warns once).
void Deduplicate(std::vector<std::string>* warnings);

std::string FormatPoles(const std::vector<std::complex<double>>& poles);

InputError RequiredExactError(std::size_t ci, const Contributor& c, const Output& out, const std::string& why);

// A source of tones only (no density): its contributors' variance is exact.
bool IsPurelyTonal(const Source& source);

// Why contributor c gets no exact variance on output o; "" when one is attempted
// (white source, pure unit scales, a stable rational path, a rational weighting).
std::string ExactRefusal(const Contributor& c, const Source& source, const Path& path, const PathAnalysis& analysis,
                         const Output& out, const ContributorSetup& setup, std::size_t o);

// The one-sided PSD of contributor ci on every output (rows: outputs),
// S_y = h S_u h^H with the output's unit and weighting factors.
// With `channel_psd`, also each source channel's part |H_rj|^2 S_jj,
// (*channel_psd)[output][channel][frequency]; with `recorder`, the path's
// responses at every f from the same evaluation of H.
std::vector<std::vector<double>> Propagate(const Budget& budget, std::size_t ci, const PathAnalysis& analysis,
                                           const InputSpectrum& input, const ContributorSetup& setup,
                                           const std::vector<double>& f,
                                           const OutputFactor& output_factor, int threads,
                                           std::vector<std::vector<std::vector<double>>>* channel_psd = nullptr,
                                           PathResponseRecorder* recorder = nullptr);

// Per output, the variance of each of the source's tones through the
// contributor's path: y = W(f0) u_out(f0) H_row(f0) (u_in(f0) .* a), with
// the unit conversions at f0 (a time derivative is j 2 pi f0).
// @throws InputError at the source's tones for a tone on a pole of the path
//   (H not finite at f0).
std::vector<std::vector<ContributorResult::Tone>> PropagateTones(const Budget& budget, std::size_t ci,
                                                                 const PathAnalysis& analysis,
                                                                 const std::vector<SpectralLine>& lines,
                                                                 const ContributorSetup& setup);

// Per tone, the variance each source channel alone gives at output o:
// |H_rj(f0) u_j|^2 with the unit conversions and the weighting at f0.
std::vector<std::vector<double>> ChannelTones(const PathAnalysis& analysis, const std::vector<SpectralLine>& lines,
                                              const ContributorSetup& setup, std::size_t o);

// cr.channels and cr.cross_variance from each channel's PSD: each channel's
// density integrated on the grid's own rule (CumulativeIntegral: Lobatto on
// panels, the power law between other points), so a part is as accurate as
// the contributor's CPS. Independent channels sum to the contributor's
// density: each interval's parts are scaled to its step, so that they add up
// to the CPS exactly (the scale differs from 1 by rounding on panels, by the
// power law's curvature between other points); correlated channels keep
// their own integrals and the cross terms take the rest. Each channel's
// tones step its CPS as they step the contributor's.
void BreakDownChannels(const Source& source, const FrequencyGrid& grid,
                       const std::vector<std::vector<double>>& channel_psd,
                       const std::vector<std::vector<double>>& channel_tones, ContributorResult* cr);

// Totals are sums of the contributors' integrals, not integrals of the total
// PSD: the power-law rule is not linear in S, and stacked CPS curves must add
// up to the total exactly. Then the band figures and band requirements.
void AddTotalsAndBands(const Output& output, const FrequencyGrid& grid, const std::vector<Band>& bands,
                       OutputResult* r);

// The references of output o on the grid, converted to its unit (a time
// derivative is (2 pi f)^2n on a PSD) and weighted as the output is.
// @throws InputError at the reference if its PSD is not finite there (a
//   conversion or weighting that overflows).
void AddReferences(const Output& output, std::size_t o, const FrequencyGrid& grid,
                   const std::vector<double>& weighting_gain2, OutputResult* r);

// The exact variance of contributor ci on output o into cr (or the reason
// there is none), and a warning where it disagrees with the grid's figure.
void AddExactVariance(const Budget& budget, std::size_t ci, std::size_t o, const PathAnalysis& analysis,
                      const ContributorSetup& setup, std::string refusal, const EngineOptions& options,
                      ContributorResult* cr, std::vector<std::string>* warnings);

// A modal path without the closed-form split (a source that is not white, a
// weighting, a derivative unit): the split of the grid integral, on the same
// grid and with the same factors as the PSD, for the outputs in `split`.
void SplitGridVarianceByMode(const Path& path, const PathAnalysis& analysis, const InputSpectrum& input,
                             const ContributorSetup& setup, const FrequencyGrid& grid,
                             const OutputFactor& output_factor, const std::vector<std::size_t>& split,
                             int threads, std::vector<OutputResult>* outputs);

// The plan, checked, with each contributor's unit conversions and rows.
FullPlan MakePlan(const Budget& budget);

}  // namespace deb::evaluation
