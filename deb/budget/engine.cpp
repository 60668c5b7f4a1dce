#include "deb/budget/engine.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <sstream>

#include "deb/budget/path_response.h"
#include "deb/core/error.h"
#include "deb/core/integrate.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/modes.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

std::string Key(const char* list, std::size_t i, const std::string& field = "") {
  std::string k = std::string(list) + "[" + std::to_string(i) + "]";
  return field.empty() ? k : k + "." + field;
}

// Natural frequency and damping of every pole with Im > 0 or real pole.
void AddResonances(const StateSpace& sys, std::vector<Resonance>* out) {
  const Eigen::VectorXcd poles = sys.Poles();
  for (Eigen::Index i = 0; i < poles.size(); ++i) {
    const std::complex<double> p = poles(i);
    const double mag = std::abs(p);
    if (mag == 0.0 || p.imag() < 0.0) continue;
    out->push_back({mag / kTwoPi, -p.real() / mag});
  }
}

std::string FormatPoles(const std::vector<std::complex<double>>& poles) {
  std::ostringstream os;
  for (std::size_t i = 0; i < poles.size() && i < 4; ++i) {
    if (i) os << ", ";
    os << poles[i].real() << (poles[i].imag() < 0 ? " - " : " + ") << std::abs(poles[i].imag()) << "j";
  }
  if (poles.size() > 4) os << ", ... (" << poles.size() << " in all)";
  return os.str();
}

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

std::vector<Band> DecadeBands(const FrequencyGrid& grid) {
  std::vector<Band> bands;
  const int k0 = static_cast<int>(std::floor(std::log10(grid.min_hz()) + 1e-12));
  const int k1 = static_cast<int>(std::ceil(std::log10(grid.max_hz()) - 1e-12));
  for (int k = k0; k < k1; ++k) {
    const double lo = std::max(std::pow(10.0, k), grid.min_hz());
    const double hi = std::min(std::pow(10.0, k + 1), grid.max_hz());
    if (hi > lo * (1.0 + 1e-9)) bands.push_back({lo, hi});
  }
  return bands;
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

}  // namespace

double OutputResult::rms() const { return std::sqrt(variance); }

bool OutputResult::pass() const { return !rms_max || rms() <= *rms_max; }

double BandRequirementResult::rms() const { return std::sqrt(variance); }

bool BandRequirementResult::pass() const { return rms() <= requirement.rms_max; }

bool OutputResult::AllPass() const {
  for (const auto& b : band_requirements)
    if (!b.pass()) return false;
  return pass();
}

std::vector<double> ReverseCps(const std::vector<double>& cps) {
  std::vector<double> r(cps.size());
  for (std::size_t i = 0; i < cps.size(); ++i) r[i] = cps.back() - cps[i];
  return r;
}

using PathAnalyses = std::map<std::string, std::shared_ptr<const PathAnalysis>>;

PathAnalyses AnalysePaths(const Budget& budget) {
  PathAnalyses paths;
  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    if (paths.count(c.path)) continue;
    const Path& path = budget.FindPath(c.path);
    std::vector<int> rows;
    for (const Output& o : budget.outputs) rows.push_back(path.OutputIndex(o.signal));
    try {
      paths[c.path] = std::make_shared<const PathAnalysis>(path, rows);
    } catch (const InputError& e) {
      if (!e.key_path().empty()) throw;
      throw InputError(Key("contributors", ci, "path"), "path '" + path.name + "': " + e.what());
    }
  }
  return paths;
}

namespace {
FrequencyGrid BuildGridUnlocated(const Budget& budget, const PathAnalyses& paths);
}  // namespace

FrequencyGrid BuildGrid(const Budget& budget) {
  budget.Validate();
  return BuildGrid(budget, AnalysePaths(budget));
}

FrequencyGrid BuildGrid(const Budget& budget, const PathAnalyses& paths) {
  try {
    return BuildGridUnlocated(budget, paths);
  } catch (const InputError& e) {
    if (!e.key_path().empty()) throw;
    throw InputError("grid", e.what());  // the grid's rules: located at the budget's grid
  }
}

namespace {
FrequencyGrid BuildGridUnlocated(const Budget& budget, const PathAnalyses& paths) {
  const GridSpec& g = budget.grid;
  switch (g.kind) {
    case GridKind::kExplicit:
      return FrequencyGrid(g.f_hz, g.panel_starts);
    case GridKind::kLog:
      return FrequencyGrid::Log(g.auto_options.min_hz, g.auto_options.max_hz, g.points);
    case GridKind::kLinear:
      return FrequencyGrid::Linear(g.auto_options.min_hz, g.auto_options.max_hz, g.points);
    case GridKind::kAuto:
      break;
  }
  AutoGridOptions options = g.auto_options;
  if (!g.range_given) {
    options.min_hz = 0.1;
    options.max_hz = 1000.0;
    for (const Band& b : budget.bands) {
      options.min_hz = std::min(options.min_hz, b.lo_hz);
      options.max_hz = std::max(options.max_hz, b.hi_hz);
    }
    for (const Output& o : budget.outputs)
      for (const BandRequirement& q : o.band_requirements) {
        options.min_hz = std::min(options.min_hz, q.lo_hz);
        options.max_hz = std::max(options.max_hz, q.hi_hz);
      }
  }
  std::vector<Resonance> resonances;
  std::vector<double> breakpoints;
  for (const auto& [name, analysis] : paths) {
    const std::vector<Resonance> r = analysis->Resonances();
    resonances.insert(resonances.end(), r.begin(), r.end());
    const Path& path = analysis->path();
    if (path.HasMeasuredData()) {
      // Every data point: between data points |H|^2 is a power law, which
      // the grid's rule integrates exactly.
      const std::vector<double> data = path.measured->DataFrequencies();
      breakpoints.insert(breakpoints.end(), data.begin(), data.end());
    }
  }
  for (const Output& o : budget.outputs)
    if (o.weighting) AddResonances(o.weighting->system, &resonances);
  for (const Source& s : budget.sources) {
    const auto b = s.spectrum->BreakpointsHz();
    breakpoints.insert(breakpoints.end(), b.begin(), b.end());
  }
  for (const Band& b : budget.bands) {
    breakpoints.push_back(b.lo_hz);
    breakpoints.push_back(b.hi_hz);
  }
  for (const Output& o : budget.outputs)
    for (const BandRequirement& q : o.band_requirements) {
      breakpoints.push_back(q.lo_hz);
      breakpoints.push_back(q.hi_hz);
    }
  // A moving average or std weights the PSD by sinc^2(pi f T) or its
  // complement, which ripples with zeros at k/T: points across each lobe
  // that the weight resolves (output_metric.h; beyond, it is smooth).
  for (const Output& o : budget.outputs) {
    if (!o.metric) continue;
    const double step_hz = 1.0 / (OutputMetric::kPointsPerLobe * o.metric->window_s);
    for (int j = 1; j <= OutputMetric::kResolvedLobes * OutputMetric::kPointsPerLobe; ++j) {
      const double f = j * step_hz;
      if (f > options.max_hz) break;
      if (f >= options.min_hz) breakpoints.push_back(f);
    }
  }
  return AutoGrid(options, resonances, breakpoints);
}
}  // namespace

BudgetResult Evaluate(const Budget& budget, const EngineOptions& options) {
  budget.Validate();
  BudgetResult result;
  result.budget_name = budget.name;
  result.paths = AnalysePaths(budget);
  result.grid = BuildGrid(budget, result.paths);
  const std::vector<double>& f = result.grid.f_hz();
  const std::size_t n = f.size();

  std::vector<Band> bands = budget.bands.empty() ? DecadeBands(result.grid) : budget.bands;
  for (std::size_t i = 0; i < budget.bands.size(); ++i) {
    const Band& b = budget.bands[i];
    if (b.lo_hz < result.grid.min_hz() * (1 - 1e-12) || b.hi_hz > result.grid.max_hz() * (1 + 1e-12)) {
      std::ostringstream os;
      os << "band [" << b.lo_hz << ", " << b.hi_hz << "] Hz extends beyond the frequency grid ["
         << result.grid.min_hz() << ", " << result.grid.max_hz() << "] Hz";
      throw InputError(Key("bands", i), os.str());
    }
  }

  // Contributors add as uncorrelated; one source feeding several of them is
  // one realisation seen through several paths, whose sum is coherent.
  for (const Source& s : budget.sources) {
    std::string users;
    int count = 0;
    for (const Contributor& c : budget.contributors)
      if (c.source == s.name) users += (count++ ? ", " : "") + ("'" + c.name + "'");
    if (count > 1)
      result.warnings.push_back("source '" + s.name + "' feeds contributors " + users +
                                ", whose variances are added as uncorrelated; if they are one disturbance seen "
                                "through several paths, join the paths (type: parallel) in one contributor");
  }

  // Weighting responses and metric factors, shared by all contributors of an output.
  std::vector<std::vector<double>> weighting_gain2(budget.outputs.size());
  for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
    const Output& out = budget.outputs[o];
    if (out.weighting) {
      const PoleStability st = ClassifyPoles(out.weighting->system.Poles());
      if (!st.unstable.empty())
        throw InputError(Key("outputs", o, "weighting"),
                         "the weighting of output '" + out.name + "' is unstable: pole(s) at " +
                             FormatPoles(st.unstable) + " rad/s");
    }
    weighting_gain2[o] = WeightingGain2(out, f, options.threads);
  }

  result.outputs.resize(budget.outputs.size());
  for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
    OutputResult& r = result.outputs[o];
    r.name = budget.outputs[o].name;
    r.signal = budget.outputs[o].signal;
    r.unit = budget.outputs[o].unit;
    r.rms_max = budget.outputs[o].rms_max;
    r.metric = budget.outputs[o].metric;
    r.total_psd.assign(n, 0.0);
  }

  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    const Source& source = budget.FindSource(c.source);
    const Path& path = budget.FindPath(c.path);
    const PathAnalysis& analysis = *result.paths.at(c.path);
    const int m = path.system.inputs();

    PoleStability stability{analysis.unstable_poles(), analysis.marginal_poles()};
    if (analysis.loop_around_data())
      result.warnings.push_back("path '" + path.name +
                                "' closes a loop around measured data: its stability is not verified "
                                "(check the loop's Nyquist plot)");
    if (!stability.unstable.empty())
      throw InputError(Key("contributors", ci, "path"),
                       "path '" + path.name + "' is unstable: pole(s) at " + FormatPoles(stability.unstable) +
                           " rad/s; a stationary output spectrum does not exist");
    if (!stability.marginal.empty())
      result.warnings.push_back("path '" + path.name + "' has pole(s) on the imaginary axis (" +
                                FormatPoles(stability.marginal) +
                                " rad/s): its variance depends on the grid's ends");

    const std::vector<UnitConversion> in_conv = InputConversions(source, path);
    bool inputs_pure_scale = true;
    for (const UnitConversion& u : in_conv) inputs_pure_scale &= u.IsPureScale();

    std::vector<int> row_of_output(budget.outputs.size());
    std::vector<UnitConversion> out_conv(budget.outputs.size());
    for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
      const Output& out = budget.outputs[o];
      const int row = path.OutputIndex(out.signal);
      row_of_output[o] = analysis.Position(row);
      out_conv[o] = OutputConversion(path, row, out);
    }

    // The factor on output o's PSD at f[k]: its unit conversion and weighting.
    const auto output_factor = [&](std::size_t o, std::size_t k) {
      const UnitConversion& u = out_conv[o];
      double factor = u.IsPureScale() ? u.scale * u.scale : u.PsdFactor(f[k]);  // no pow() when not needed
      if (!weighting_gain2[o].empty()) factor *= weighting_gain2[o][k];
      return factor;
    };
    std::vector<std::vector<double>> psd(budget.outputs.size(), std::vector<double>(n, 0.0));
    const InputSpectrum input(*source.spectrum, in_conv);
    try {
      analysis.ForEachResponse(
          f,
          [&](std::size_t k, const Eigen::MatrixXcd& h) {
            // Allocates only where the spectrum must be evaluated per frequency.
            Eigen::VectorXd diag_scratch;
            Eigen::MatrixXcd full_scratch;
            const Eigen::VectorXd* s_diag = input.diagonal() ? &input.Diagonal(f[k], diag_scratch) : nullptr;
            const Eigen::MatrixXcd* s_full = input.diagonal() ? nullptr : &input.Full(f[k], full_scratch);
            for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
              const int row = row_of_output[o];
              double s = s_diag ? DiagonalForm(h, row, *s_diag) : HermitianForm(h, row, *s_full);
              psd[o][k] = std::max(s * output_factor(o, k), 0.0);  // rounding of a PSD-valued S_u
            }
          },
          options.threads);
    } catch (const InputError& e) {
      // A pole on the grid, data (spectrum or response) that do not reach: point at the contributor.
      if (!e.key_path().empty()) throw;
      throw InputError(Key("contributors", ci), "contributor '" + c.name + "': " + e.what());
    }

    for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
      const Output& out = budget.outputs[o];
      for (std::size_t k = 0; k < n; ++k) {
        if (!std::isfinite(psd[o][k])) {
          std::ostringstream os;
          os << "contributor '" << c.name << "' gives a non-finite PSD on output '" << out.name << "' at "
             << f[k] << " Hz (a pole on the frequency axis, or a source that is not finite there)";
          throw InputError(Key("contributors", ci), os.str());
        }
      }
      ContributorResult cr;
      cr.name = c.name;
      cr.psd = std::move(psd[o]);
      cr.cps = CumulativeIntegral(result.grid, cr.psd);
      cr.variance = cr.cps.back();
      cr.tail_variance_estimate = TailEstimate(f, cr.psd);

      // Exact variance: white source, pure unit scales, stable strictly proper path.
      const auto white = source.spectrum->WhiteLevel();
      std::string why_not;
      if (c.exact == ExactVariance::kOff) why_not = "not requested";
      else if (path.HasMeasuredData())
        why_not = "the path holds measured frequency data (no state-space model for a Lyapunov solution)";
      else if (!white) why_not = "the source is not white (exact variance needs a flat spectrum without band limits)";
      else if (!inputs_pure_scale || !out_conv[o].IsPureScale())
        why_not = "the units differ by a time derivative (a factor j 2 pi f is not a rational path)";
      else if (!stability.marginal.empty()) why_not = "the path has poles on the imaginary axis";
      else if (out.metric)
        why_not = "the " + ToString(out.metric->type) +
                  " weighting |sinc(pi f T)|^2 is not rational in s: no Lyapunov form";
      if (why_not.empty()) {
        const int row = path.OutputIndex(out.signal);
        Eigen::MatrixXd in_scale = Eigen::MatrixXd::Zero(m, m);
        for (int j = 0; j < m; ++j) in_scale(j, j) = in_conv[j].scale;
        const Eigen::MatrixXd w_two_sided = in_scale * (*white) * in_scale / 2.0;
        try {
          const PathAnalysis::ExactVariance exact =
              analysis.Exact(row, w_two_sided, out.weighting ? &out.weighting->system : nullptr);
          const double scale2 = out_conv[o].scale * out_conv[o].scale;
          cr.exact_variance = exact.variance * scale2;
          if (exact.mode_share.size() > 0) {
            cr.top_modes = TopModes(*path.modal, exact.mode_share, exact.variance, *cr.exact_variance);
            cr.top_modes_of = ModeSplit::kExactVariance;
          }
        } catch (const InputError& e) {
          why_not = e.what();
        }
      }
      if (!cr.exact_variance) {
        cr.exact_note = why_not;
        if (c.exact == ExactVariance::kRequired)
          throw InputError(Key("contributors", ci, "exact"),
                           "exact variance of contributor '" + c.name + "' on output '" + out.name +
                               "' is required but cannot be computed: " + why_not);
      } else if (*cr.exact_variance > 0.0) {
        // With tails that do not converge as power laws (no estimate), the
        // grid figure alone is compared.
        const bool tails = std::isfinite(cr.tail_variance_estimate);
        const double beyond = tails ? cr.tail_variance_estimate : 0.0;
        const double rel = std::abs(*cr.exact_variance - (cr.variance + beyond)) / *cr.exact_variance;
        if (rel > options.exact_tolerance) {
          std::ostringstream os;
          os << "contributor '" << c.name << "' on output '" << out.name << "': exact variance "
             << *cr.exact_variance << " and grid variance " << cr.variance;
          if (tails) os << " (+ " << beyond << " estimated beyond the grid)";
          else os << " (no estimate beyond the grid: its ends are not power-law tails)";
          os << " differ by " << rel << " relative; refine the grid or widen its range";
          result.warnings.push_back(os.str());
        }
      }
      OutputResult& r = result.outputs[o];
      for (std::size_t k = 0; k < n; ++k) r.total_psd[k] += cr.psd[k];
      r.contributors.push_back(std::move(cr));
    }

    // A modal path without the closed-form split (a source that is not
    // white, a weighting, a derivative unit): the split of the grid
    // integral, on the same grid and with the same factors as the PSD.
    if (analysis.modal()) {
      std::vector<std::size_t> split;
      for (std::size_t o = 0; o < budget.outputs.size(); ++o)
        if (result.outputs[o].contributors.back().top_modes.empty()) split.push_back(o);
      if (!split.empty()) {
        const std::vector<double> q = LinearQuadratureWeights(result.grid);
        std::vector<int> positions;
        std::vector<std::vector<double>> weight;
        for (const std::size_t o : split) {
          positions.push_back(row_of_output[o]);
          std::vector<double> w(n);
          for (std::size_t k = 0; k < n; ++k) w[k] = output_factor(o, k);
          weight.push_back(std::move(w));
        }
        const Eigen::MatrixXd parts = analysis.ModeParts(
            f, q, positions, weight,
            [&input](double f_hz, Eigen::MatrixXcd& scratch) -> const Eigen::MatrixXcd& {
              return input.Full(f_hz, scratch);
            },
            options.threads);
        for (std::size_t i = 0; i < split.size(); ++i) {
          ContributorResult& cr = result.outputs[split[i]].contributors.back();
          double whole = 0.0;  // the PSD's integral by the same linear rule
          for (std::size_t k = 0; k < n; ++k) whole += q[k] * cr.psd[k];
          cr.top_modes = TopModes(*path.modal, parts.col(static_cast<Eigen::Index>(i)), whole, cr.variance);
          cr.top_modes_of = ModeSplit::kGridVariance;
        }
      }
    }
  }

  // A path shared by several contributors warns once.
  std::vector<std::string> unique;
  for (std::string& w : result.warnings)
    if (std::find(unique.begin(), unique.end(), w) == unique.end()) unique.push_back(std::move(w));
  result.warnings = std::move(unique);

  // Totals are sums of the contributors' integrals, not integrals of the total
  // PSD: the power-law rule is not linear in S, and stacked CPS curves must
  // add up to the total exactly.
  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    OutputResult& r = result.outputs[o];
    r.total_cps.assign(n, 0.0);
    for (const auto& cr : r.contributors)
      for (std::size_t k = 0; k < n; ++k) r.total_cps[k] += cr.cps[k];
    r.variance = r.total_cps.back();
    for (const Band& b : bands) {
      BandResult br;
      br.band = b;
      for (const auto& cr : r.contributors) {
        br.contributor_variance.push_back(IntegralBetween(result.grid, cr.psd, cr.cps, b.lo_hz, b.hi_hz));
        br.variance += br.contributor_variance.back();
      }
      r.bands.push_back(std::move(br));
    }
    const auto& limits = budget.outputs[o].band_requirements;
    for (std::size_t b = 0; b < limits.size(); ++b) {
      const BandRequirement& q = limits[b];
      if (q.lo_hz < result.grid.min_hz() * (1 - 1e-12) || q.hi_hz > result.grid.max_hz() * (1 + 1e-12)) {
        std::ostringstream os;
        os << "band requirement [" << q.lo_hz << ", " << q.hi_hz << "] Hz extends beyond the frequency grid ["
           << result.grid.min_hz() << ", " << result.grid.max_hz() << "] Hz";
        throw InputError(Key("outputs", o) + ".band_requirements[" + std::to_string(b) + "]", os.str());
      }
      BandRequirementResult br;
      br.requirement = q;
      for (const auto& cr : r.contributors) br.variance += IntegralBetween(result.grid, cr.psd, cr.cps, q.lo_hz, q.hi_hz);
      r.band_requirements.push_back(br);
    }
  }
  return result;
}

}  // namespace deb
