// Block-diagram algebra on paths: series, parallel and feedback of paths that
// are already built, with units checked and scaled at every junction (a
// junction from um to nm is a gain of 1000; from um to um/s it is a time
// derivative and is refused). Rational parts are joined in state space
// (interconnect.h); a part with measured data makes the result a diagram
// evaluated per frequency (frequency_model.h). A modal part makes it a
// diagram too, for H (the modal form at each frequency), and is realised
// in state space beside it, 2 states per mode, up to
// limits::kMaxDenseStates states, for poles and the exact variance; a
// larger one is kept as its parts only (Path::KeptAsParts), up to
// limits::kMaxCoupledStates states.
//   series    H = H_n ... H_2 H_1
//   parallel  H = H_1 + ... + H_n
//   feedback  H = (I - sign G K)^-1 G   (sign = -1: negative feedback)
#pragma once

#include <string>
#include <vector>

#include "deb/budget/path.h"

namespace deb {

// A part of a composition and where the caller named it: errors about the
// part are InputErrors with this key path (empty: none).
struct PathPart {
  const Path* path = nullptr;
  std::string key_path;
};

// The composed path takes the first part's inputs (names and units) and the
// last part's outputs (series) or the first part's outputs (parallel); the
// caller sets its name and description.
// @throws InputError (at a part's key path) for fewer than two parts, sizes
//   that do not fit, units that differ by more than a scale, or (without
//   one) a result of more than limits::kMaxCoupledStates states.
Path SeriesOfPaths(const std::vector<PathPart>& parts);
Path ParallelOfPaths(const std::vector<PathPart>& parts);
// The loop closed by `controller` around `plant`: the plant's inputs and
// outputs; the controller must map the plant's outputs to its inputs.
// @throws InputError as above, and if the loop's I - sign G K is singular.
Path FeedbackOfPaths(const PathPart& plant, const PathPart& controller, int sign = -1);

// The path driven through the named inputs only (a contributor's `inputs:`):
// H restricted to those columns, in the order given, with their names and
// units; a modal path stays modal, a measured one is a column selection of
// its data, its loops are kept. `name` and `description` are the path's.
// @throws InputError "path 'plant' has no input 'u9' (did you mean 'u2'?)"
//   for an unknown name, and for an empty list or a name given twice.
Path SelectPathInputs(const Path& path, const std::vector<std::string>& inputs);

// One term of a combined output: weight [unit] times a path output signal.
struct SignalTerm {
  std::string signal;
  double weight = 1.0;
  std::string unit = "1";  // of the weight
};

// The path with one more output row, `name` = sum_i weight_i signal_i (a
// line of sight or an image shift as a weighted sum of node motions), in
// the unit of the first term (its weight's unit times its signal's); every
// term must convert to it by a pure scale. The row is formed from H's rows
// (state space: C and D rows; modal: mode-shape rows; measured: a gain after
// the data), so that cross terms are exact: its PSD is not a sum of PSDs.
// @throws InputError (the key path ".<signal>" of the offending term, for the
//   caller to prefix) for a signal the path lacks, a unit that does not fit,
//   no terms, or a name the path already has.
Path AddCombinedOutput(const Path& path, const std::string& name, const std::vector<SignalTerm>& terms);

// @throws InputError unless sign is -1 (negative feedback) or +1.
void CheckFeedbackSign(int sign);

}  // namespace deb
