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

// Variance of a power law continued beyond the grid ends through the first and
// last two points; infinite where the power law does not converge.
double TailEstimate(const std::vector<double>& f, const std::vector<double>& s) {
  const std::size_t n = f.size();
  double tail = 0.0;
  if (s[0] > 0.0 && s[1] > 0.0) {
    const double a = std::log(s[1] / s[0]) / std::log(f[1] / f[0]);
    tail += a > -1.0 ? s[0] * f[0] / (a + 1.0) : std::numeric_limits<double>::infinity();
  }
  if (s[n - 1] > 0.0 && s[n - 2] > 0.0) {
    const double a = std::log(s[n - 1] / s[n - 2]) / std::log(f[n - 1] / f[n - 2]);
    tail += a < -1.0 ? s[n - 1] * f[n - 1] / (-(a + 1.0)) : std::numeric_limits<double>::infinity();
  }
  return tail;
}

// sum_j |h_rj|^2 s_j: row r of h through uncorrelated inputs.
double DiagonalForm(const Eigen::MatrixXcd& h, int r, const Eigen::VectorXd& s) {
  double y = 0.0;
  for (Eigen::Index j = 0; j < h.cols(); ++j) y += std::norm(h(r, j)) * s(j);
  return y;
}

// Re(h_r S h_r^H) for Hermitian S, from its diagonal and upper triangle:
// sum_j |h_rj|^2 S_jj + 2 Re(conj(h_rj) sum_{i<j} h_ri S_ij). Written in real
// arithmetic: std::complex products carry NaN checks that triple the cost.
double HermitianForm(const Eigen::MatrixXcd& h, int r, const Eigen::MatrixXcd& s) {
  double y = 0.0;
  for (Eigen::Index j = 0; j < h.cols(); ++j) {
    double ur = 0.0, ui = 0.0;
    for (Eigen::Index i = 0; i < j; ++i) {
      const double hr = h(r, i).real(), hi = h(r, i).imag(), sr = s(i, j).real(), si = s(i, j).imag();
      ur += hr * sr - hi * si;
      ui += hr * si + hi * sr;
    }
    y += std::norm(h(r, j)) * s(j, j).real() + 2.0 * (ur * h(r, j).real() + ui * h(r, j).imag());
  }
  return y;
}

// The one-sided PSD of contributor ci on every output (rows: outputs),
// S_y = h S_u h^H with the output's unit and weighting factors.
// With `channel_psd`, also each source channel's part |H_rj|^2 S_jj,
// (*channel_psd)[output][channel][frequency].
std::vector<std::vector<double>> Propagate(const Budget& budget, std::size_t ci, const PathAnalysis& analysis,
                                           const InputSpectrum& input, const ContributorSetup& setup,
                                           const std::vector<double>& f,
                                           const OutputFactor& output_factor, int threads,
                                           std::vector<std::vector<std::vector<double>>>* channel_psd,
                                           PathResponseRecorder* recorder) {
  const Contributor& c = budget.contributors[ci];
  const std::size_t n = f.size();
  std::vector<std::vector<double>> psd(budget.outputs.size(), std::vector<double>(n, 0.0));
  const Eigen::Index channels = budget.FindSource(c.source).spectrum->channels();
  if (channel_psd)
    channel_psd->assign(budget.outputs.size(),
                        std::vector<std::vector<double>>(static_cast<std::size_t>(channels), std::vector<double>(n, 0.0)));
  try {
    analysis.ForEachResponse(
        f,
        [&](std::size_t k, const Eigen::MatrixXcd& h) {
          if (recorder) recorder->Record(k, h);
          // Allocates only where the spectrum must be evaluated per frequency.
          Eigen::VectorXd diag_scratch;
          Eigen::MatrixXcd full_scratch;
          const Eigen::VectorXd* s_diag = input.diagonal() ? &input.Diagonal(f[k], diag_scratch) : nullptr;
          const Eigen::MatrixXcd* s_full = input.diagonal() ? nullptr : &input.Full(f[k], full_scratch);
          for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
            const int row = setup.row_of_output[o];
            double s = s_diag ? DiagonalForm(h, row, *s_diag) : HermitianForm(h, row, *s_full);
            psd[o][k] = std::max(s * output_factor(o, k), 0.0);  // rounding of a PSD-valued S_u
            if (channel_psd)
              for (Eigen::Index j = 0; j < channels; ++j) {
                const double sjj = s_diag ? (*s_diag)(j) : (*s_full)(j, j).real();
                (*channel_psd)[o][static_cast<std::size_t>(j)][k] =
                    std::max(std::norm(h(row, j)) * sjj * output_factor(o, k), 0.0);
              }
          }
        },
        threads);
  } catch (const InputError& e) {
    // A pole on the grid, a loop singular at a grid point: point at the contributor.
    if (!e.key_path().empty()) throw;
    throw InputError(Key("contributors", ci), "contributor '" + c.name + "': " + e.what());
  }
  for (std::size_t o = 0; o < budget.outputs.size(); ++o)
    for (std::size_t k = 0; k < n; ++k)
      if (!std::isfinite(psd[o][k])) {
        std::ostringstream os;
        os << "contributor '" << c.name << "' gives a non-finite PSD on output '" << budget.outputs[o].name
           << "' at " << f[k] << " Hz (a pole on the frequency axis, or a source that is not finite there)";
        throw InputError(Key("contributors", ci), os.str());
      }
  return psd;
}

// Per output, the variance of each of the source's tones through the
// contributor's path: y = W(f0) u_out(f0) H_row(f0) (u_in(f0) .* a), with
// the unit conversions at f0 (a time derivative is j 2 pi f0).
// @throws InputError at the source's tones for a tone on a pole of the path
//   (H not finite at f0).
std::vector<std::vector<ContributorResult::Tone>> PropagateTones(const Budget& budget, std::size_t ci,
                                                                 const PathAnalysis& analysis,
                                                                 const std::vector<SpectralLine>& lines,
                                                                 const ContributorSetup& setup) {
  if (lines.empty()) return {};
  const Contributor& c = budget.contributors[ci];
  const std::string at = Key("sources", IndexOf(budget.sources, c.source), "spectrum.tones");
  std::vector<double> f0;  // on the grid's range: CheckToneCoverage
  for (const SpectralLine& l : lines) f0.push_back(l.f_hz);
  const std::size_t outputs = budget.outputs.size();
  std::vector<std::vector<ContributorResult::Tone>> tones(outputs, std::vector<ContributorResult::Tone>(lines.size()));
  try {
    analysis.ForEachResponse(
        f0,
        [&](std::size_t k, const Eigen::MatrixXcd& h) {
          Eigen::VectorXcd u = lines[k].rms;
          for (Eigen::Index j = 0; j < u.size(); ++j) u(j) *= setup.in_conv[j].ResponseFactor(f0[k]);
          for (std::size_t o = 0; o < outputs; ++o) {
            const std::complex<double> y = (h.row(setup.row_of_output[o]) * u)(0) *
                                           setup.out_conv[o].ResponseFactor(f0[k]);
            tones[o][k] = {f0[k], std::norm(y)};
          }
        },
        1);
  } catch (const InputError& e) {
    std::ostringstream os;
    os << "a tone of source '" << c.source << "' sits on a pole of path '" << c.path << "' (contributor '" << c.name
       << "'): " << e.message();
    throw InputError(at, os.str());
  }
  for (std::size_t o = 0; o < outputs; ++o) {
    const std::vector<double> w2 = WeightingGain2(budget.outputs[o], f0, 1);
    for (std::size_t k = 0; k < lines.size(); ++k) {
      if (!w2.empty()) tones[o][k].variance *= w2[k];
      if (!std::isfinite(tones[o][k].variance)) {
        std::ostringstream os;
        os << "the tone at " << f0[k] << " Hz of source '" << c.source << "' gives a non-finite variance on output '"
           << budget.outputs[o].name << "' (a pole of the path or the weighting at the tone)";
        throw InputError(at, os.str());
      }
    }
  }
  return tones;
}

// Per tone, the variance each source channel alone gives at output o:
// |H_rj(f0) u_j|^2 with the unit conversions and the weighting at f0.
std::vector<std::vector<double>> ChannelTones(const PathAnalysis& analysis, const std::vector<SpectralLine>& lines,
                                              const ContributorSetup& setup, std::size_t o) {
  std::vector<std::vector<double>> v(lines.size());
  if (lines.empty()) return v;
  std::vector<double> f0;
  for (const SpectralLine& l : lines) f0.push_back(l.f_hz);
  analysis.ForEachResponse(
      f0,
      [&](std::size_t k, const Eigen::MatrixXcd& h) {
        const Eigen::VectorXcd& a = lines[k].rms;
        for (Eigen::Index j = 0; j < a.size(); ++j) {
          const std::complex<double> y = h(setup.row_of_output[o], j) * a(j) *
                                         setup.in_conv[static_cast<std::size_t>(j)].ResponseFactor(f0[k]) *
                                         setup.out_conv[o].ResponseFactor(f0[k]);
          v[k].push_back(std::norm(y));
        }
      },
      1);
  return v;
}

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
                       const std::vector<std::vector<double>>& channel_tones, ContributorResult* cr) {
  const std::vector<double>& f = grid.f_hz();
  // The density's CPS alone (tones taken out again).
  std::vector<double> density = cr->cps;
  for (const ContributorResult::Tone& t : cr->tones) {
    AddToneStep(f, t.f_hz, -t.variance, &density);
  }
  std::vector<std::vector<double>> own;
  for (const std::vector<double>& psd : channel_psd) own.push_back(CumulativeIntegral(grid, psd));
  std::vector<double> scale(f.size(), 1.0);
  if (source.spectrum->IsDiagonal())
    for (std::size_t k = 1; k < f.size(); ++k) {
      double sum = 0.0;
      for (const std::vector<double>& c : own) sum += c[k] - c[k - 1];
      scale[k] = sum > 0.0 ? (density[k] - density[k - 1]) / sum : 0.0;
    }
  double parts = 0.0;
  for (std::size_t j = 0; j < channel_psd.size(); ++j) {
    ContributorResult::ChannelPart p;
    p.channel = j < source.channel_names.size() ? source.channel_names[j] : std::to_string(j + 1);
    p.psd = channel_psd[j];
    p.cps.assign(f.size(), 0.0);
    for (std::size_t k = 1; k < f.size(); ++k) p.cps[k] = p.cps[k - 1] + scale[k] * (own[j][k] - own[j][k - 1]);
    for (std::size_t t = 0; t < cr->tones.size(); ++t) AddToneStep(f, cr->tones[t].f_hz, channel_tones[t][j], &p.cps);
    p.variance = p.cps.back();
    parts += p.variance;
    cr->channels.push_back(std::move(p));
  }
  cr->cross_variance = source.spectrum->IsDiagonal() && cr->tones.empty() ? 0.0 : cr->variance - parts;
}

// Totals are sums of the contributors' integrals, not integrals of the total
// PSD: the power-law rule is not linear in S, and stacked CPS curves must add
// up to the total exactly. Then the band figures and band requirements.
void AddTotalsAndBands(const Output& output, const FrequencyGrid& grid, const std::vector<Band>& bands,
                       OutputResult* r) {
  const std::size_t n = grid.size();
  r->total_psd.assign(n, 0.0);
  r->total_cps.assign(n, 0.0);
  for (const auto& cr : r->contributors)
    for (std::size_t k = 0; k < n; ++k) {
      r->total_psd[k] += cr.psd[k];
      r->total_cps[k] += cr.cps[k];
    }
  r->variance = r->total_cps.back();
  for (const Band& b : bands) {
    BandResult br;
    br.band = b;
    for (const auto& cr : r->contributors) {
      br.contributor_variance.push_back(ContributorVarianceBetween(grid, cr, b.lo_hz, b.hi_hz));
      br.variance += br.contributor_variance.back();
    }
    r->bands.push_back(std::move(br));
  }
  for (const BandRequirement& q : output.band_requirements) {
    BandRequirementResult br;
    br.requirement = q;
    for (const auto& cr : r->contributors) br.variance += ContributorVarianceBetween(grid, cr, q.lo_hz, q.hi_hz);
    r->band_requirements.push_back(br);
  }
}

// The references of output o on the grid, converted to its unit (a time
// derivative is (2 pi f)^2n on a PSD) and weighted as the output is.
// @throws InputError at the reference if its PSD is not finite there (a
//   conversion or weighting that overflows).
void AddReferences(const Output& output, std::size_t o, const FrequencyGrid& grid,
                   const std::vector<double>& weighting_gain2, OutputResult* r) {
  const std::vector<double>& f = grid.f_hz();
  for (std::size_t i = 0; i < output.references.size(); ++i) {
    const Source& ref = output.references[i];
    ReferenceResult rr;
    rr.name = ref.name;
    const UnitConversion conv = ConvertUnit(ref.unit, output.unit);
    const std::optional<FrequencyInterval> defined = ref.spectrum->DefinedRangeHz();
    rr.covered_lo_hz = defined ? std::max(defined->lo_hz, grid.min_hz()) : grid.min_hz();
    rr.covered_hi_hz = defined ? std::min(defined->hi_hz, grid.max_hz()) : grid.max_hz();
    rr.psd.assign(f.size(), 0.0);
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (f[k] < rr.covered_lo_hz || f[k] > rr.covered_hi_hz) continue;
      double s = ref.spectrum->Psd(f[k])(0) * conv.PsdFactor(f[k]);
      if (!weighting_gain2.empty()) s *= weighting_gain2[k];
      if (!std::isfinite(s)) {
        std::ostringstream os;
        os << "reference '" << ref.name << "' has a PSD of " << s << " " << output.unit << "^2/Hz at " << f[k]
           << " Hz in the unit of output '" << output.name << "' (" << ref.unit << " -> " << output.unit
           << (weighting_gain2.empty() ? "" : ", weighted") << "): the converted values leave the range of a double";
        throw InputError(Key("outputs", o, "references[" + std::to_string(i) + "]"), os.str());
      }
      rr.psd[k] = std::max(s, 0.0);
    }
    rr.cps = CumulativeIntegral(grid, rr.psd);
    rr.variance = rr.cps.back();
    rr.budget_variance = IntegralBetween(grid, r->total_psd, r->total_cps, rr.covered_lo_hz, rr.covered_hi_hz);
    for (const BandResult& b : r->bands)
      rr.band_variance.push_back(b.band.lo_hz >= rr.covered_lo_hz && b.band.hi_hz <= rr.covered_hi_hz
                                     ? std::optional<double>(IntegralBetween(grid, rr.psd, rr.cps, b.band.lo_hz,
                                                                             b.band.hi_hz))
                                     : std::nullopt);
    r->references.push_back(std::move(rr));
  }
}

}  // namespace evaluation

}  // namespace deb
