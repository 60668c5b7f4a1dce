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

constexpr double kDefaultGridMinHz = 0.1;  // the automatic grid without a range
constexpr double kDefaultGridMaxHz = 1000.0;

std::string Key(const char* list, std::size_t i, const std::string& field) {
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

using PathAnalyses = std::map<std::string, std::shared_ptr<const PathAnalysis>>;

FrequencyGrid BuildGridUnlocated(const Budget& budget, const PathAnalyses& paths);


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

  // A sampled block's response is periodic in f: above its Nyquist frequency
  // the grid sees its images, which a continuous-time signal there aliases.
  for (const auto& [key, analysis] : plan.paths) {
    const Path& path = analysis->path();
    if (!path.measured) continue;
    for (const IrrationalBlock& b : path.measured->IrrationalBlocks())
      if (b.nyquist_hz() > 0.0 && plan.grid.max_hz() > b.nyquist_hz())
        plan.warnings.push_back("path '" + path.name + "' holds " + b.Describe() + ", evaluated up to " +
                                SignificantText(plan.grid.max_hz()) + " Hz, above its Nyquist frequency " +
                                SignificantText(b.nyquist_hz()) +
                                " Hz: there its response repeats (H(e^(j w T)) is periodic) and a signal aliases; "
                                "end the grid at the Nyquist frequency (grid.max_hz) or read those bands with that "
                                "in mind");
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

}  // namespace evaluation

using namespace evaluation;

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

EvaluationPlan PlanEvaluation(const Budget& budget) {
  try {
    return MakePlan(budget).plan;
  } catch (const InputError& e) {
    throw budget.Locate(e);  // at file:line:col, from the positions recorded at load
  }
}

}  // namespace deb
