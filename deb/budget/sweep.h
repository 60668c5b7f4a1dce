// Parameter sweeps: one budget evaluated over a set of values of some of its
// numeric parameters (an isolator's height, the skyhook gains, a source
// level), named by key path as in error messages, e.g.
// "paths[0].isolators[*].position[2]". Values come as lists or linear / log
// ranges, combined as a full grid (every combination; the last parameter
// varies fastest) or zipped (the i-th value of every parameter together).
// The YAML loader builds the variants (deb/load/sweep_yaml.h); the results
// become one CSV row per variant.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "deb/budget/result.h"
#include "deb/core/study_shard.h"
#include "deb/core/enum_names.h"

namespace deb {

enum class SweepMode { kGrid, kZip };
inline constexpr EnumName<SweepMode> kSweepModeNames[] = {{SweepMode::kGrid, "grid"}, {SweepMode::kZip, "zip"}};
constexpr EnumNames<SweepMode> NamesOf(SweepMode) { return kSweepModeNames; }
// @throws InputError listing allowed values.
inline SweepMode ParseSweepMode(const std::string& text) { return ParseEnum<SweepMode>(text, "sweep mode"); }

struct SweepParameter {
  std::string key_path;        // into the budget file; [*] means every element
  std::vector<double> values;  // not empty
  // A textual parameter (e.g. a VC class): the values are the indices
  // 0, 1, ... into texts, which the budget receives.
  std::vector<std::string> texts;
  std::string label;  // how axes and tables name it (`label:`); empty: the key path
  std::string unit;   // of its values (`unit:`, UDUNITS-2), for axes and tables; may be empty

  // Written after each number the budget file receives: the unit of a
  // budget parameter the sweep varies ("N/m"), or "".
  std::string value_unit;
  // The value as the budget file receives it: a number (and value_unit), or
  // texts[index].
  std::string Text(double value) const;
  // For tables and axes: a number to 4 significant digits, or texts[index].
  std::string ShortText(double value) const;
  // label, or the key path.
  std::string Name() const;
  // "label [unit]", "label", or the key path.
  std::string AxisTitle() const;
  // "label = value unit" (ShortText), e.g. "isolator height h = -210 mm".
  std::string Setting(double value) const;
};

// The longest `label:` of a sweep parameter (it must fit an axis).
inline constexpr std::size_t kMaxSweepLabelChars = 60;

// What is wrong with a parameter's label (a sweep's `label:`, deb
// sensitivity --label): blank, longer than kMaxSweepLabelChars, or holding a
// control character; "" when it is one line of printable text that fits.
std::string ParameterLabelProblem(const std::string& label);

struct SweepSpec {
  SweepMode mode = SweepMode::kGrid;
  std::vector<SweepParameter> parameters;

  // One row per variant, one value per parameter. DEB_DEMANDs non-empty
  // values and, for kZip, equal lengths (the loader checks both).
  std::vector<std::vector<double>> Variants() const;
};

// count values from `from` to `to` inclusive, evenly spaced (linear) or
// evenly spaced in log (both ends > 0). @throws InputError for count < 1 or
// log ends <= 0.
std::vector<double> LinearRange(double from, double to, int count);
std::vector<double> LogRange(double from, double to, int count);

// Evaluates every variant, `threads` variants at a time (<= 0: the default
// count): each is one job (ParallelForEach), variant(i) loading variant i
// (row i of spec.Variants()) and the engine evaluating it single-threaded,
// so the results are bitwise the same for any thread count.
// progress(done, total) is called after each variant from the thread that
// finished it, one call at a time (may be empty).
// @throws InputError of the first variant that fails (as a serial loop
//   would): variant(i)'s own, or the engine's naming the variant's values.
std::vector<BudgetResult> EvaluateSweep(const SweepSpec& spec, const std::function<Budget(std::size_t)>& variant,
                                        int threads,
                                        const std::function<void(std::size_t, std::size_t)>& progress = {});
// The variants of one shard of the sweep (its block of spec.Variants()'s
// rows), as EvaluateSweep evaluates them; progress over the block.
std::vector<BudgetResult> EvaluateSweepPart(const SweepSpec& spec, const std::function<Budget(std::size_t)>& variant,
                                            const StudyShard& shard, int threads,
                                            const std::function<void(std::size_t, std::size_t)>& progress = {});
// Variants [begin, end) of spec.Variants(), as EvaluateSweep evaluates them:
// a block of a distributed sweep.
std::vector<BudgetResult> EvaluateSweepRange(const SweepSpec& spec, const std::function<Budget(std::size_t)>& variant,
                                             std::size_t begin, std::size_t end, int threads,
                                             const std::function<void(std::size_t, std::size_t)>& progress = {});
// The same for variants already loaded.
std::vector<BudgetResult> EvaluateSweep(const SweepSpec& spec, const std::vector<Budget>& variants, int threads,
                                        const std::function<void(std::size_t, std::size_t)>& progress = {});

// CSV: one row per variant: the parameter values, then per output its RMS
// and the RMS of every contributor ("<output>.rms", "<output>.<contributor>.rms").
std::string SweepCsv(const SweepSpec& spec, const std::vector<BudgetResult>& results);

}  // namespace deb
