#include "deb/budget/output_covariance.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <set>

#include "deb/budget/path_response.h"
#include "deb/budget/response_traces.h"
#include "deb/budget/result.h"
#include "deb/core/error.h"
#include "deb/core/integrate.h"
#include "deb/core/suggest.h"
#include "deb/spectra/tone_spectrum.h"

namespace deb {
namespace {

using Complex = std::complex<double>;

std::string Entry(std::size_t i) { return "covariance[" + std::to_string(i) + "]"; }

// h[a](i, k) = h_k(f_i) on output a of the set, from ComputePathResponses.
std::vector<Eigen::MatrixXcd> Transfers(const std::vector<PathResponse>& responses,
                                        const std::vector<std::size_t>& index, std::size_t n) {
  std::vector<Eigen::MatrixXcd> h;
  for (const std::size_t o : index) {
    const PathResponse& r = responses[o];
    const std::size_t m = r.gain2.size();
    Eigen::MatrixXcd t(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
    for (std::size_t k = 0; k < m; ++k) {
      DEB_DEMAND(r.gain2[k].size() == n && r.phase_rad[k].size() == n);
      for (std::size_t i = 0; i < n; ++i)
        t(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) =
            std::polar(std::sqrt(r.gain2[k][i]), r.phase_rad[k][i]);
    }
    h.push_back(std::move(t));
  }
  return h;
}

// Re(y_a conj(y_b)) summed over the source's tones, y = h(f0) a (exact).
Eigen::MatrixXd ToneCovariance(const Budget& budget, const BudgetResult& result, std::size_t ci,
                               const std::vector<std::size_t>& index) {
  const std::size_t p = index.size();
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(p));
  const std::vector<SpectralLine> lines = budget.FindSource(budget.contributors[ci].source).spectrum->Lines();
  if (lines.empty()) return t;
  std::vector<double> f0;
  for (const SpectralLine& l : lines) f0.push_back(l.f_hz);
  const std::vector<Eigen::MatrixXcd> h = Transfers(ComputePathResponses(budget, result, ci, f0, 1), index, f0.size());
  for (std::size_t k = 0; k < lines.size(); ++k) {
    Eigen::VectorXcd y(static_cast<Eigen::Index>(p));
    for (std::size_t a = 0; a < p; ++a) y(static_cast<Eigen::Index>(a)) = (h[a].row(static_cast<Eigen::Index>(k)) * lines[k].rms).value();
    t += (y * y.adjoint()).real();
  }
  return (t + t.transpose()) / 2.0;
}

// The grid's linear-rule integral of Re(h_a S_u h_b^H) (the density part).
Eigen::MatrixXd GridCovariance(const Spectrum& spectrum, const std::vector<Eigen::MatrixXcd>& h,
                               const std::vector<double>& f, const std::vector<double>& q) {
  const Eigen::Index p = static_cast<Eigen::Index>(h.size());
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(p, p);
  const bool diagonal = spectrum.IsDiagonal();
  Eigen::MatrixXcd g(p, spectrum.channels());  // rows: h_a(f_i)
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (q[i] == 0.0) continue;
    for (Eigen::Index a = 0; a < p; ++a) g.row(a) = h[static_cast<std::size_t>(a)].row(static_cast<Eigen::Index>(i));
    Eigen::MatrixXcd s;
    if (diagonal) s = spectrum.Psd(f[i]).cast<Complex>().asDiagonal();
    else s = spectrum.Csd(f[i]);
    l += q[i] * (g * s * g.adjoint()).real();
  }
  return l;
}

Eigen::MatrixXd Correlation(const Eigen::MatrixXd& cov) {
  Eigen::MatrixXd r(cov.rows(), cov.cols());
  for (Eigen::Index a = 0; a < cov.rows(); ++a)
    for (Eigen::Index b = 0; b < cov.cols(); ++b) {
      const double d = std::sqrt(cov(a, a) * cov(b, b));
      r(a, b) = d > 0.0 ? cov(a, b) / d : std::numeric_limits<double>::quiet_NaN();
    }
  return r;
}

}  // namespace

void ValidateCovarianceRequest(const Budget& budget) {
  const std::vector<std::string>& names = budget.covariance;
  if (names.empty()) return;
  std::vector<std::string> outputs;
  for (const Output& o : budget.outputs) outputs.push_back(o.name);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::size_t o = 0;
    while (o < outputs.size() && outputs[o] != names[i]) ++o;
    if (o == outputs.size())
      throw InputError(Entry(i), "no output named '" + names[i] + "'" + DidYouMean(names[i], outputs) +
                                     ": covariance lists outputs of the budget");
    if (!seen.insert(names[i]).second)
      throw InputError(Entry(i), "output '" + names[i] + "' is named twice in covariance: each output once");
    const Output& out = budget.outputs[o];
    if (out.metric)
      throw InputError(Entry(i), "output '" + names[i] + "' has a " + ToString(out.metric->type) +
                                     " metric and no covariance with other outputs: a moving std is not a linear "
                                     "function of the signal, and a moving average's PSD factor has no phase "
                                     "(list the output without its metric instead)");
  }
  if (names.size() < 2)
    throw InputError("covariance", "covariance needs at least 2 outputs, got " + std::to_string(names.size()) +
                                       " (one output's variance is its RMS squared)");
}

CovarianceResult ComputeOutputCovariance(const Budget& budget, const BudgetResult& result, int threads) {
  CovarianceResult cov;
  for (const std::string& name : budget.covariance) {
    std::size_t o = 0;
    while (o < budget.outputs.size() && budget.outputs[o].name != name) ++o;
    DEB_DEMAND(o < budget.outputs.size() && o < result.outputs.size());
    cov.outputs.push_back(name);
    cov.units.push_back(budget.outputs[o].unit);
    cov.index.push_back(o);
  }
  const Eigen::Index p = static_cast<Eigen::Index>(cov.index.size());
  DEB_DEMAND(p >= 2);
  const std::vector<double>& f = result.grid.f_hz();
  const std::vector<double> q = LinearQuadratureWeights(result.grid);
  cov.matrix = Eigen::MatrixXd::Zero(p, p);
  Eigen::MatrixXd exact = Eigen::MatrixXd::Zero(p, p);
  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    const Source& source = budget.FindSource(c.source);
    const bool tonal = dynamic_cast<const ToneSpectrum*>(source.spectrum.get()) != nullptr;
    const Eigen::MatrixXd tones = ToneCovariance(budget, result, ci, cov.index);
    Eigen::MatrixXd m = tones;
    if (!tonal) {
      // The engine's traces hold these responses on this grid when it keeps
      // them (EngineOptions::response_traces): the path is evaluated once.
      // Transfers rebuilds h from |h|^2 and arg h either way.
      const bool on_grid = result.traces && std::all_of(result.traces->paths.at(ci).begin(),
                                                        result.traces->paths.at(ci).end(),
                                                        [](const PathResponse& r) { return r.f_hz.empty(); });
      std::vector<PathResponse> evaluated;
      if (!on_grid) evaluated = ComputePathResponses(budget, result, ci, f, threads);
      const std::vector<PathResponse>& responses = on_grid ? result.traces->paths.at(ci) : evaluated;
      const std::vector<Eigen::MatrixXcd> h = Transfers(responses, cov.index, f.size());
      const Eigen::MatrixXd l = GridCovariance(*source.spectrum, h, f, q);
      Eigen::VectorXd d(p);  // the engine's density variance over the linear rule's
      for (Eigen::Index a = 0; a < p; ++a) {
        const ContributorResult& cr = result.outputs[cov.index[static_cast<std::size_t>(a)]].contributors[ci];
        double density = cr.variance;
        for (const ContributorResult::Tone& t : cr.tones) density -= t.variance;
        d(a) = l(a, a) > 0.0 ? std::sqrt(std::max(density, 0.0) / l(a, a)) : 0.0;
      }
      const Eigen::MatrixXd scaled = d.asDiagonal() * l * d.asDiagonal();
      m += (scaled + scaled.transpose()) / 2.0;  // symmetric exactly, not to rounding
    }
    for (Eigen::Index a = 0; a < p; ++a)
      m(a, a) = result.outputs[cov.index[static_cast<std::size_t>(a)]].contributors[ci].variance;
    cov.matrix += m;
    cov.contributors.push_back({c.name, std::move(m)});

    // The exact part of this contributor, while every one so far has one.
    if (!cov.exact_note.empty()) continue;
    for (Eigen::Index a = 0; a < p && cov.exact_note.empty(); ++a) {
      const std::size_t o = cov.index[static_cast<std::size_t>(a)];
      const ContributorResult& cr = result.outputs[o].contributors[ci];
      if (!cr.exact_variance)
        cov.exact_note = "contributor '" + c.name + "' has no exact variance on output '" +
                         cov.outputs[static_cast<std::size_t>(a)] +
                         "': " + cr.exact_note;
    }
    if (!cov.exact_note.empty()) continue;
    if (tonal) {
      exact += tones;
      continue;
    }
    const PathAnalysis& analysis = *result.paths.at(ContributorPathKey(c));
    const Path& path = analysis.path();
    std::vector<int> rows;
    std::vector<const StateSpace*> weightings;
    Eigen::VectorXd scale(p);
    for (Eigen::Index a = 0; a < p; ++a) {
      const Output& out = budget.outputs[cov.index[static_cast<std::size_t>(a)]];
      rows.push_back(path.OutputIndex(out.signal));
      weightings.push_back(out.weighting ? &out.weighting->system : nullptr);
      scale(a) = OutputConversion(path, rows.back(), out).scale;  // pure scales: ExactRefusal
    }
    try {
      const Eigen::MatrixXd x =
          analysis.ExactCovariance(rows, weightings, WhiteInputIntensity(source, InputConversions(source, path)));
      const Eigen::MatrixXd scaled = scale.asDiagonal() * x * scale.asDiagonal();
      exact += (scaled + scaled.transpose()) / 2.0 + tones;
    } catch (const InputError& e) {
      cov.exact_note = "contributor '" + c.name + "': " + e.message();
    }
  }
  for (Eigen::Index a = 0; a < p; ++a) cov.matrix(a, a) = result.outputs[cov.index[static_cast<std::size_t>(a)]].variance;
  cov.correlation = Correlation(cov.matrix);
  if (cov.exact_note.empty()) cov.exact_matrix = exact;
  return cov;
}

}  // namespace deb
