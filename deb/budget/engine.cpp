#include "deb/budget/engine.h"
#include "deb/budget/response_traces.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "deb/budget/path_composition.h"
#include "deb/budget/path_response.h"
#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/spectra/tone_spectrum.h"
#include "deb/core/integrate.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/modes.h"
#include "deb/units/unit.h"

namespace deb {
namespace {

constexpr double kDefaultGridMinHz = 0.1;  // the automatic grid without a range
constexpr double kDefaultGridMaxHz = 1000.0;
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

// The powers of ten strictly inside (min_hz, max_hz).
std::vector<double> DecadesWithin(double min_hz, double max_hz) {
  std::vector<double> decades;
  const int k0 = static_cast<int>(std::floor(std::log10(min_hz) + 1e-12));
  const int k1 = static_cast<int>(std::ceil(std::log10(max_hz) - 1e-12));
  for (int k = k0; k <= k1; ++k) {
    const double f = std::pow(10.0, k);
    if (f > min_hz && f < max_hz) decades.push_back(f);
  }
  return decades;
}

// One band per decade, the grid's ends cutting the first and last: the
// bands between its ends and the powers of ten inside it (which the
// automatic grid makes grid points, BuildGrid).
std::vector<Band> DecadeBands(const FrequencyGrid& grid) {
  std::vector<double> edges = {grid.min_hz()};
  for (const double f : DecadesWithin(grid.min_hz(), grid.max_hz())) edges.push_back(f);
  edges.push_back(grid.max_hz());
  std::vector<Band> bands;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i)
    if (edges[i + 1] > edges[i] * (1.0 + 1e-9)) bands.push_back({edges[i], edges[i + 1]});
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

using PathAnalyses = std::map<std::string, std::shared_ptr<const PathAnalysis>>;

PathAnalyses AnalysePaths(const Budget& budget) {
  PathAnalyses paths;
  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    const std::string key = ContributorPathKey(c);
    if (paths.count(key)) continue;
    const Path& full = budget.FindPath(c.path);
    // Validate checked the names and the combinations.
    const Path path = WithOutputCombinations(c.inputs.empty() ? full : SelectPathInputs(full, c.inputs), budget.outputs);
    std::vector<int> rows;
    for (const Output& o : budget.outputs) rows.push_back(path.OutputIndex(o.signal));
    try {
      paths[key] = std::make_shared<const PathAnalysis>(path, rows);
    } catch (const InputError& e) {
      if (!e.key_path().empty()) throw;
      throw InputError(Key("contributors", ci, "path"), "path '" + path.name + "': " + e.what());
    }
  }
  return paths;
}

namespace {

FrequencyGrid BuildGridUnlocated(const Budget& budget, const PathAnalyses& paths);

// The position of the item named `name` in the budget's sources or paths (Budget::Validate: it exists).
template <typename Item>
std::size_t IndexOf(const std::vector<Item>& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name) return i;
  DEB_DEMAND(false);
  return 0;
}

// The range every contributor's tabulated data (measured spectra, measured
// responses that may not be extrapolated) covers; nullopt when unlimited.
std::optional<FrequencyInterval> DataRange(const Budget& budget) {
  std::optional<FrequencyInterval> range;
  for (const Contributor& c : budget.contributors) {
    range = Intersect(range, budget.FindSource(c.source).spectrum->DefinedRangeHz());
    const Path& path = budget.FindPath(c.path);
    if (path.HasMeasuredData()) range = Intersect(range, path.measured->DefinedRangeHz());
  }
  return range;
}

std::string RangeText(double lo_hz, double hi_hz) {
  std::ostringstream os;
  os << "[" << lo_hz << ", " << hi_hz << "] Hz";
  return os.str();
}

// A grid that reaches beyond tabulated data that may not be extrapolated
// would fail during propagation: rejected here, at the data (or at the grid
// when the budget set its range).
void CheckDataCoverage(const Budget& budget, const FrequencyGrid& grid) {
  const bool grid_set = budget.grid.kind != GridKind::kAuto || budget.grid.range_given;
  const auto message = [&](const std::string& what, const FrequencyInterval& r, const std::string& whose) {
    return what + " is defined over " + RangeText(r.lo_hz, r.hi_hz) +
           " only (extrapolation: error), but the frequency grid spans " + RangeText(grid.min_hz(), grid.max_hz()) +
           (grid_set ? ": keep the grid inside that range"
                     : ": the automatic grid covers every band and band requirement; keep them inside that range") +
           ", or set " + whose + " extrapolation (hold or zero)";
  };
  for (const Contributor& c : budget.contributors) {
    const std::size_t si = IndexOf(budget.sources, c.source);
    const Source& source = budget.sources[si];
    if (const auto r = source.spectrum->DefinedRangeHz(); r && !r->Contains(grid.min_hz(), grid.max_hz()))
      throw InputError(grid_set ? std::string("grid") : Key("sources", si, "spectrum"),
                       message("source '" + source.name + "'", *r, "the source's"));
    const std::size_t pi = IndexOf(budget.paths, c.path);
    const Path& path = budget.paths[pi];
    if (!path.HasMeasuredData()) continue;
    if (const auto r = path.measured->DefinedRangeHz(); r && !r->Contains(grid.min_hz(), grid.max_hz()))
      throw InputError(grid_set ? std::string("grid") : Key("paths", pi),
                       message("path '" + path.name + "' (measured data)", *r, "the measured response's"));
  }
}

// Every tone of a contributor's source lies on the grid's range (a tone has
// no density for the grid to find: it is evaluated at f0 itself).
void CheckToneCoverage(const Budget& budget, const FrequencyGrid& grid) {
  for (const Contributor& c : budget.contributors) {
    const std::size_t si = IndexOf(budget.sources, c.source);
    for (const SpectralLine& l : budget.sources[si].spectrum->Lines())
      if (l.f_hz < grid.min_hz() || l.f_hz > grid.max_hz()) {
        std::ostringstream os;
        os << "the tone at " << l.f_hz << " Hz of source '" << c.source << "' lies outside the frequency grid ["
           << grid.min_hz() << ", " << grid.max_hz() << "] Hz: widen the grid (min_hz, max_hz) to reach it";
        throw InputError(Key("sources", si, "spectrum.tones"), os.str());
      }
  }
}

// Every reference that may not be extrapolated overlaps the grid: it is
// compared with the budget over the overlap (AddReferences), and an empty
// overlap leaves nothing to compare.
void CheckReferenceCoverage(const Budget& budget, const FrequencyGrid& grid) {
  for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
    const std::vector<Source>& references = budget.outputs[o].references;
    for (std::size_t i = 0; i < references.size(); ++i) {
      const auto r = references[i].spectrum->DefinedRangeHz();
      if (!r || std::max(r->lo_hz, grid.min_hz()) < std::min(r->hi_hz, grid.max_hz())) continue;
      throw InputError(Key("outputs", o, "references[" + std::to_string(i) + "].spectrum"),
                       "reference '" + references[i].name + "' is defined over " + RangeText(r->lo_hz, r->hi_hz) +
                           " only (extrapolation: error), which does not overlap the frequency grid " +
                           RangeText(grid.min_hz(), grid.max_hz()) +
                           ": there is no band to compare it with the budget in; widen the grid to reach it, or set "
                           "the reference's extrapolation (hold or zero)");
    }
  }
}

// The unit conversions and output rows of one contributor.
struct ContributorSetup {
  std::vector<UnitConversion> in_conv;  // per path input
  bool inputs_pure_scale = true;
  std::vector<int> row_of_output;          // per budget output: its position in the analysis
  std::vector<UnitConversion> out_conv;  // per budget output
};

ContributorSetup SetUp(const Budget& budget, const Source& source, const Path& path, const PathAnalysis& analysis) {
  ContributorSetup s;
  s.in_conv = InputConversions(source, path);
  for (const UnitConversion& u : s.in_conv) s.inputs_pure_scale &= u.IsPureScale();
  for (const Output& out : budget.outputs) {
    const int row = path.OutputIndex(out.signal);
    s.row_of_output.push_back(analysis.Position(row));
    s.out_conv.push_back(OutputConversion(path, row, out));
  }
  return s;
}

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
    return "the units differ by a time derivative (a factor j 2 pi f is not a rational path)";
  if (!analysis.marginal_poles().empty()) return "the path has poles on the imaginary axis";
  if (out.metric)
    return "the " + ToString(out.metric->type) + " weighting |sinc(pi f T)|^2 is not rational in s: no Lyapunov form";
  return "";
}

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
    // 0.1-1000 Hz, inside the data that may not be extrapolated (all of the
    // data when it lies outside that range), widened to every band.
    options.min_hz = kDefaultGridMinHz;
    options.max_hz = kDefaultGridMaxHz;
    if (const auto data = DataRange(budget); data && data->lo_hz < data->hi_hz) {
      options.min_hz = std::max(options.min_hz, data->lo_hz);
      options.max_hz = std::min(options.max_hz, data->hi_hz);
      if (!(options.min_hz < options.max_hz)) {
        options.min_hz = data->lo_hz;
        options.max_hz = data->hi_hz;
      }
    }
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
  for (const Output& o : budget.outputs)  // a reference's band edges too: it is integrated on the same grid
    for (const Source& r : o.references) {
      const auto b = r.spectrum->BreakpointsHz();
      breakpoints.insert(breakpoints.end(), b.begin(), b.end());
    }
  for (const Band& b : budget.bands) {
    breakpoints.push_back(b.lo_hz);
    breakpoints.push_back(b.hi_hz);
  }
  if (budget.bands.empty())  // the default bands' edges (DecadeBands) are grid points too
    for (const double decade_hz : DecadesWithin(options.min_hz, options.max_hz)) breakpoints.push_back(decade_hz);
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

void CheckBandsInGrid(const Budget& budget, const FrequencyGrid& grid) {
  const auto outside = [&grid](double lo, double hi) { return !grid.Covers(lo, hi); };
  const std::string grid_text = RangeText(grid.min_hz(), grid.max_hz());
  for (std::size_t i = 0; i < budget.bands.size(); ++i) {
    const Band& b = budget.bands[i];
    if (outside(b.lo_hz, b.hi_hz))
      throw InputError(Key("bands", i), "band " + RangeText(b.lo_hz, b.hi_hz) +
                                            " extends beyond the frequency grid " + grid_text);
  }
  for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
    const auto& limits = budget.outputs[o].band_requirements;
    for (std::size_t b = 0; b < limits.size(); ++b)
      if (outside(limits[b].lo_hz, limits[b].hi_hz))
        throw InputError(Key("outputs", o) + ".band_requirements[" + std::to_string(b) + "]",
                         "band requirement " + RangeText(limits[b].lo_hz, limits[b].hi_hz) +
                             " extends beyond the frequency grid " + grid_text);
  }
}

// Keeps the first of each repeated warning (a path shared by several contributors warns once).
void Deduplicate(std::vector<std::string>* warnings) {
  std::vector<std::string> unique;
  for (std::string& w : *warnings)
    if (std::find(unique.begin(), unique.end(), w) == unique.end()) unique.push_back(std::move(w));
  *warnings = std::move(unique);
}

}  // namespace

namespace {

// The plan, and the unit conversions and rows of every contributor it
// worked out, which Evaluate reuses.
struct FullPlan {
  EvaluationPlan plan;
  std::vector<ContributorSetup> setups;  // per contributor
};

FullPlan MakePlan(const Budget& budget) {
  budget.Validate();
  FullPlan full;
  EvaluationPlan& plan = full.plan;
  plan.paths = AnalysePaths(budget);
  plan.grid = BuildGrid(budget, plan.paths);
  CheckBandsInGrid(budget, plan.grid);
  CheckDataCoverage(budget, plan.grid);
  CheckToneCoverage(budget, plan.grid);
  CheckReferenceCoverage(budget, plan.grid);
  plan.bands = budget.bands.empty() ? DecadeBands(plan.grid) : budget.bands;
  plan.loops = AnalyseLoops(budget, plan.grid.f_hz());
  for (const LoopResult& loop : plan.loops) {
    const std::string name = "the loop of '" + loop.plant + "' closed by '" + loop.controller + "'";
    if (!loop.evaluated)
      plan.warnings.push_back(name + ": no margins computed: " + loop.note);
    else if (loop.margins.modulus_margin < kLowModulusMargin)
      plan.warnings.push_back(name + " comes within " + SignificantText(loop.margins.modulus_margin) + " of -1 at " +
                              SignificantText(loop.margins.modulus_margin_f_hz) +
                              " Hz (modulus margin; |S| peaks at " +
                              SignificantText(ToDecibel(1.0 / loop.margins.modulus_margin)) + " dB; " +
                              SignificantText(kLowModulusMargin) + " or more is usual)");
  }

  for (const Source& s : budget.sources)
    for (const std::string& note : s.notes) plan.warnings.push_back("source '" + s.name + "': " + note);

  // Contributors add as uncorrelated; one source feeding several of them is
  // one realisation seen through several paths, whose sum is coherent.
  for (const Source& s : budget.sources) {
    std::string users;
    int count = 0;
    for (const Contributor& c : budget.contributors)
      if (c.source == s.name) users += (count++ ? ", " : "") + ("'" + c.name + "'");
    if (count > 1)
      plan.warnings.push_back("source '" + s.name + "' feeds contributors " + users +
                              ", whose variances are added as uncorrelated; if they are one disturbance seen "
                              "through several paths, join the paths (type: parallel) in one contributor");
  }

  for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
    const Output& out = budget.outputs[o];
    if (!out.weighting) continue;
    const PoleStability st = ClassifyPoles(out.weighting->system.Poles());
    if (!st.unstable.empty())
      throw InputError(Key("outputs", o, "weighting"), "the weighting of output '" + out.name +
                                                           "' is unstable: pole(s) at " + FormatPoles(st.unstable) +
                                                           " rad/s");
  }

  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    const Source& source = budget.FindSource(c.source);
    const PathAnalysis& analysis = *plan.paths.at(ContributorPathKey(c));
    const Path& path = analysis.path();
    if (analysis.loop_around_data())
      plan.warnings.push_back("path '" + path.name +
                              "' closes a loop around measured data: its stability is not verified by poles "
                              "(read the loop's margins: deb check, or summary.json's loops)");
    if (!analysis.unstable_poles().empty())
      throw InputError(Key("contributors", ci, "path"),
                       "path '" + path.name + "' is unstable: pole(s) at " + FormatPoles(analysis.unstable_poles()) +
                           " rad/s; a stationary output spectrum does not exist");
    if (!analysis.marginal_poles().empty())
      plan.warnings.push_back("path '" + path.name + "' has pole(s) on the imaginary axis (" +
                              FormatPoles(analysis.marginal_poles()) +
                              " rad/s): its variance depends on the grid's ends");
    ContributorSetup setup = SetUp(budget, source, path, analysis);
    std::vector<std::string> refusals;
    for (std::size_t o = 0; o < budget.outputs.size(); ++o) {
      refusals.push_back(ExactRefusal(c, source, path, analysis, budget.outputs[o], setup, o));
      if (c.exact == ExactVariance::kRequired && !refusals.back().empty())
        throw RequiredExactError(ci, c, budget.outputs[o], refusals.back());
    }
    plan.exact_refusal.push_back(std::move(refusals));
    full.setups.push_back(std::move(setup));
  }
  Deduplicate(&plan.warnings);
  return full;
}

}  // namespace

EvaluationPlan PlanEvaluation(const Budget& budget) {
  try {
    return MakePlan(budget).plan;
  } catch (const InputError& e) {
    throw budget.Locate(e);  // at file:line:col, from the positions recorded at load
  }
}

namespace {

// The one-sided PSD of contributor ci on every output (rows: outputs),
// S_y = h S_u h^H with the output's unit and weighting factors.
// With `channel_psd`, also each source channel's part |H_rj|^2 S_jj,
// (*channel_psd)[output][channel][frequency].
std::vector<std::vector<double>> Propagate(const Budget& budget, std::size_t ci, const PathAnalysis& analysis,
                                           const InputSpectrum& input, const ContributorSetup& setup,
                                           const std::vector<double>& f,
                                           const OutputFactor& output_factor, int threads,
                                           std::vector<std::vector<std::vector<double>>>* channel_psd = nullptr) {
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

  for (std::size_t ci = 0; ci < budget.contributors.size(); ++ci) {
    const Contributor& c = budget.contributors[ci];
    const Source& source = budget.FindSource(c.source);
    const PathAnalysis& analysis = *result.paths.at(ContributorPathKey(c));
    const Path& path = analysis.path();
    const ContributorSetup& setup = full.setups[ci];
    const OutputFactor output_factor{setup.out_conv, weighting_gain2, f};
    const InputSpectrum input(*source.spectrum, setup.in_conv);
    std::vector<std::vector<std::vector<double>>> channel_psd;
    std::vector<std::vector<double>> psd = Propagate(budget, ci, analysis, input, setup, f, output_factor,
                                                     options.threads, c.breakdown_channels ? &channel_psd : nullptr);
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
      if (c.breakdown_channels)
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
    result.traces = std::make_shared<const ResponseTraces>(ComputeResponseTraces(budget, result, options.threads));
  if (!budget.covariance.empty()) result.covariance = ComputeOutputCovariance(budget, result, options.threads);
  return result;
}

}  // namespace

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
