// What Evaluate gives back (engine.h): per output its total and every
// contributor's PSD and CPS on one frequency grid, variances, bands,
// requirements and measured references; the feedback loops with their
// margins; the output covariance; and the outline of the budget (names,
// units, descriptions; no model). The types are plain data, and a result
// read back from its store (deb/results/result_store.h) is the same type: the
// result files and the report are functions of a result alone, and what
// reads a result includes this header, not the engine's.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/budget_outline.h"
#include "deb/budget/loop_analysis.h"
#include "deb/budget/output_covariance.h"
#include "deb/budget/path_analysis.h"
#include "deb/core/enum_names.h"
#include "deb/core/frequency_grid.h"

namespace deb {

struct ResponseTraces;  // response_traces.h

// One mode's part of a contributor's variance on an output (modal paths).
// Output r is the sum of the modes' responses y_k, and its PSD splits as
// S_r = sum_k Re(S_{y_k y_r}): mode k's part is the cross-spectrum of its
// own response with the whole output, so that the parts of all modes add up
// to the variance (with a static residual, less the residual's part). Under
// a white source with an exact variance this is the symmetric split of the
// modal covariance (modal_response.h), over 0..infinity; otherwise the same
// split of the grid's integral (PathAnalysis::ModeParts).
struct ModeShare {
  int mode = 0;        // 1-based, in the order of the path's mode table
  double f_hz = 0.0;
  double zeta = 0.0;
  double variance = 0.0;  // output unit^2; negative where the mode cancels others
  double share = 0.0;     // variance / the variance split (ModeSplit)
};

// Which variance ContributorResult::top_modes split.
enum class ModeSplit { kNone, kExactVariance, kGridVariance };
inline constexpr EnumName<ModeSplit> kModeSplitNames[] = {{ModeSplit::kNone, "none"},
                                                          {ModeSplit::kExactVariance, "exact_variance"},
                                                          {ModeSplit::kGridVariance, "grid_variance"}};
constexpr EnumNames<ModeSplit> NamesOf(ModeSplit) { return kModeSplitNames; }

struct ContributorResult {
  std::string name;
  std::string source;  // the budget's source and path names: a result
  std::string path;    // describes itself without the Budget beside it
  std::vector<std::string> inputs;  // the path inputs it drives (Contributor::inputs); empty: all
  std::string group;                // Contributor::group ("stage/amplifier"), or empty
  // The source's tones (tone_spectrum.h) at this output, each propagated
  // exactly: variance |H(f0) a|^2 (output unit^2). Included in `cps` (a step
  // at the first grid point >= f_hz) and `variance`, not in `psd`.
  struct Tone {
    double f_hz = 0.0;
    double variance = 0.0;
  };
  std::vector<Tone> tones;
  // `breakdown: channels`: the part of each source channel j, |H_rj|^2 S_jj
  // (its PSD, CPS and variance; with the channel's tones). With independent
  // channels they add up to the contributor exactly; with correlated ones
  // the rest, 2 Re sum_{i<j} conj(H_ri) S_ij H_rj, is `cross_variance` (it
  // may be negative: correlation can cancel).
  struct ChannelPart {
    std::string channel;
    std::vector<double> psd, cps;
    double variance = 0.0;
  };
  std::vector<ChannelPart> channels;
  double cross_variance = 0.0;
  std::vector<double> psd;  // one-sided, output unit^2/Hz, per grid point
  std::vector<double> cps;  // forward CPS, output unit^2
  double variance = 0.0;    // cps.back()
  std::optional<double> exact_variance;  // Lyapunov, over 0..infinity
  std::string exact_note;                // why there is none, if none
  double tail_variance_estimate = 0.0;   // power-law extrapolation beyond the grid
  // Modal path: the modes with the largest |share|, largest first (at most
  // kTopModes), of the exact variance where there is one, else of the grid
  // variance.
  std::vector<ModeShare> top_modes;
  ModeSplit top_modes_of = ModeSplit::kNone;
  static constexpr std::size_t kTopModes = 10;
};

struct BandResult {
  Band band;
  double variance = 0.0;
  std::vector<double> contributor_variance;  // same order as OutputResult::contributors
};

struct BandRequirementResult {
  BandRequirement requirement;
  double variance = 0.0;  // of the output within the band

  double rms() const;
  bool pass() const;
};

// A measured spectrum of an output (Output::references), in the output's
// unit and weighting, on the grid: compared with the budget, not summed.
struct ReferenceResult {
  std::string name;
  std::vector<double> psd, cps;  // one-sided, output unit^2/Hz; 0 outside `covered`
  double variance = 0.0;         // over the covered part of the grid
  double budget_variance = 0.0;  // the output's (the budget's) over the same part
  // The part of the grid where the measurement is defined.
  double covered_lo_hz = 0.0, covered_hi_hz = 0.0;
  // Per OutputResult::bands: its variance, or none where the band is not
  // covered by the measurement.
  std::vector<std::optional<double>> band_variance;
};

struct OutputResult {
  std::string name;
  std::string signal;
  std::string unit;
  std::vector<ContributorResult> contributors;
  std::vector<double> total_psd;
  std::vector<double> total_cps;
  double variance = 0.0;
  std::optional<double> rms_max;
  std::optional<OutputMetric> metric;  // variance is then E[MA^2] or E[MSD^2]
  std::vector<BandResult> bands;
  std::vector<BandRequirementResult> band_requirements;
  std::vector<ReferenceResult> references;

  double rms() const;
  bool pass() const;      // the whole-grid requirement; true when there is none
  bool AllPass() const;   // pass() and every band requirement
};

struct BudgetResult {
  // The budget's names, descriptions, units and contributors: what the
  // result files and the report say of it (budget_outline.h).
  BudgetOutline outline;
  FrequencyGrid grid{std::vector<double>{1.0, 2.0}};
  std::vector<OutputResult> outputs;
  std::vector<std::string> warnings;
  // The analysis of every contributor's path by name, built once by
  // Evaluate and shared with the report (path plots).
  std::map<std::string, std::shared_ptr<const PathAnalysis>> paths;
  // Every distinct feedback loop of the contributors' paths, with its margins.
  std::vector<LoopResult> loops;
  // The covariance of the outputs the budget's `covariance:` lists
  // (output_covariance.h); none when it lists none.
  std::optional<CovarianceResult> covariance;
  // What the report draws of the paths and loops (response_traces.h), or
  // null (EngineOptions::response_traces). The report needs nothing else of
  // the models: a result read back from its store has traces, no paths.
  std::shared_ptr<const ResponseTraces> traces;
};

// Reverse CPS: integral of S from f to f_max, from a forward CPS.
std::vector<double> ReverseCps(const std::vector<double>& cps);

// A tone's step in a CPS (ContributorResult::tones): `variance` added from
// the first point of f_hz at or above tone_f_hz on (a negative variance takes
// the step out again).
void AddToneStep(const std::vector<double>& f_hz, double tone_f_hz, double variance, std::vector<double>* cps);

// The variance of a contributor between lo_hz and hi_hz (within the grid):
// the integral of its density (IntegralBetween on its CPS) plus each of its
// tones with lo_hz < f0 <= hi_hz, exactly; a band from the grid's first point
// is closed there (lo_hz <= f0), as the CPS counts a tone on that point.
double ContributorVarianceBetween(const FrequencyGrid& grid, const ContributorResult& c, double lo_hz, double hi_hz);

}  // namespace deb
