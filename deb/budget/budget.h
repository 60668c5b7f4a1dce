// An error budget as deb evaluates it: sources, paths, contributors (source x
// path), outputs (a named signal of the paths, in a declared unit, optionally
// through a weighting filter), frequency bands and requirements. The YAML
// loader builds one; the engine evaluates it. Validate() checks every cross
// reference and unit, naming the key path of the offending entry.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/output_metric.h"
#include "deb/budget/path.h"
#include "deb/budget/path_composition.h"
#include "deb/budget/source.h"
#include "deb/core/enum_names.h"
#include "deb/core/frequency_grid.h"
#include "deb/core/key_positions.h"
#include "deb/parameters/parameter_set.h"
#include "deb/systems/state_space.h"

namespace deb {

enum class GridKind { kAuto, kLog, kLinear, kExplicit };
inline constexpr EnumName<GridKind> kGridKindNames[] = {
    {GridKind::kAuto, "auto"}, {GridKind::kLog, "log"}, {GridKind::kLinear, "linear"},
    {GridKind::kExplicit, "explicit"}};
constexpr EnumNames<GridKind> NamesOf(GridKind) { return kGridKindNames; }
// @throws InputError listing allowed values.
inline GridKind ParseGridKind(const std::string& text) { return ParseEnum<GridKind>(text, "grid type"); }

struct GridSpec {
  GridKind kind = GridKind::kAuto;
  // kAuto: range and densities; when range_given is false the range is
  // [0.1, 1000] Hz widened to cover every band.
  AutoGridOptions auto_options;
  bool range_given = false;
  int points = 1000;            // kLog, kLinear
  std::vector<double> f_hz;     // kExplicit
  // kExplicit: the panels of a grid built before (FrequencyGrid::panel_starts),
  // to evaluate a variant on exactly the nominal's rule; empty from YAML.
  std::vector<std::size_t> panel_starts;
};

// The spec of `grid` itself, points and panels: a variant evaluated on it
// integrates on exactly the nominal's rule (no refinement around moving
// poles to add noise to a difference).
GridSpec ExplicitGrid(const FrequencyGrid& grid);

// A SISO filter applied to a signal to form an output, e.g. the thesis'
// leaky integrator 1/(s + 0.02 pi) that turns a velocity into a "position".
struct Weighting {
  StateSpace system = StateSpace::Gain(Eigen::MatrixXd::Identity(1, 1));
  std::string unit = "1";  // unit of the filter's gain (s for an integrator)
  std::string description;
};

// An RMS limit on one frequency band of an output, in the output's unit.
struct BandRequirement {
  double lo_hz = 0.0;
  double hi_hz = 0.0;
  double rms_max = 0.0;
};

struct Output {
  std::string name;
  std::string signal;  // output row name in every contributor's path
  std::string unit;
  std::optional<Weighting> weighting;
  std::optional<OutputMetric> metric;  // moving average / std over a window, after the weighting
  std::optional<double> rms_max;  // requirement, in `unit`
  std::vector<BandRequirement> band_requirements;
  // Measured spectra of this output (one channel each): drawn and compared
  // with the budget, never summed (OutputResult::references).
  std::vector<Source> references;
  // A weighted sum of signals (AddCombinedOutput); then `signal` is the
  // output's name, the row that every contributor's path gains.
  std::vector<SignalTerm> combination;
};

// The path with a row for every output that combines signals, named after
// the output. @throws InputError at "outputs[o].combination[.signal]".
Path WithOutputCombinations(const Path& path, const std::vector<Output>& outputs);

// Whether a contributor gets an exact (Lyapunov) variance beside its CPS.
// kAuto: whenever the source is white and the path stable; kRequired: an
// error if that is not possible; kOff: never.
enum class ExactVariance { kAuto, kRequired, kOff };
inline constexpr EnumName<ExactVariance> kExactVarianceNames[] = {
    {ExactVariance::kAuto, "auto"}, {ExactVariance::kRequired, "required"}, {ExactVariance::kOff, "off"}};
constexpr EnumNames<ExactVariance> NamesOf(ExactVariance) { return kExactVarianceNames; }
// @throws InputError listing allowed values.
inline ExactVariance ParseExactVariance(const std::string& text) {
  return ParseEnum<ExactVariance>(text, "exact-variance mode");
}

struct Contributor {
  std::string name;
  std::string source;
  std::string path;
  ExactVariance exact = ExactVariance::kAuto;
  // The path inputs the source drives, by name, one per source channel in
  // order (SelectPathInputs); empty: all of them, in the path's order.
  std::vector<std::string> inputs;
  // The group it belongs to, a path of names from the top ("stage/amplifier",
  // groups.h); empty: none (a top-level term).
  std::string group;
  // `breakdown: channels`: also the part of each source channel
  // (ContributorResult::channels).
  bool breakdown_channels = false;
};

// The key of the path a contributor drives: the path's name, with the
// inputs it selects, e.g. "plant(u2)"; the key of BudgetResult::paths and
// EvaluationPlan::paths.
std::string ContributorPathKey(const Contributor& c);

struct Band {
  double lo_hz = 0.0;
  double hi_hz = 0.0;
};

// A physical model behind some of the paths, described for `deb model`.
struct ModelReport {
  std::string name;
  // Plain text: natural frequencies, mode shapes, pre-stress; computed when
  // asked (an eigen-analysis a study's thousands of variants do not need).
  std::function<std::string()> report;
};

struct Budget {
  std::string name;
  std::string description;
  std::string source_file;  // where it was loaded from, if anywhere
  // Where each key path stands in source_file, recorded when it was loaded
  // (null for a budget built in code): see Locate.
  std::shared_ptr<const KeyPositions> positions;
  GridSpec grid;
  std::vector<Source> sources;
  std::vector<Path> paths;
  std::vector<Contributor> contributors;
  std::vector<Output> outputs;
  std::vector<Band> bands;
  std::vector<ModelReport> models;
  // `covariance:`: outputs whose covariance matrix is reported
  // (output_covariance.h); empty: none. Validate checks the rules.
  std::vector<std::string> covariance;
  // `parameters:`, evaluated (deb/parameters/parameter_set.h), in the order
  // written; the numbers above already hold their values.
  std::vector<Parameter> parameters;
  bool has_sweep = false;  // the file has a `sweep` section (read by deb sweep, checked by deb check)
  std::size_t uncertain_parameters = 0;  // parameters with a `distribution:` (sampled by deb uncertainty)

  // Checks names, references, channel counts and units.
  // @throws InputError with the key path (e.g. "contributors[2].path").
  void Validate() const;

  // e at file:line:col of its key path in the file loaded (e itself if it
  // has no key path or a file already, or the budget was not loaded).
  InputError Locate(const InputError& e) const;

  // @throws InputError at "sources" / "paths" naming the nearest name if there is none of that name.
  const Source& FindSource(const std::string& name) const;
  const Path& FindPath(const std::string& name) const;
};

}  // namespace deb
