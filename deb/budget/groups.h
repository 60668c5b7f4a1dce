// Groups of contributors: a budget of 30-200 terms is a tree (stage ->
// amplifier, DAC, encoder; floor -> VC, measured). A contributor names its
// group as a path of names from the top, `group: stage/amplifier`; groups
// nest to any depth (up to kMaxGroupDepth). Every group's variance is the
// sum of its members' (contributors are uncorrelated, docs/method.md,
// convention 6), over the whole grid and in every band.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "deb/budget/result.h"

namespace deb {

inline constexpr std::size_t kMaxGroupDepth = 16;

// The segments of a group path ("stage/amplifier" -> {stage, amplifier}).
// @throws InputError for an empty segment ("stage//x", "/stage", "stage/"),
//   a segment with characters other than letters, digits, _ - . and space,
//   the reserved name "total", or more than kMaxGroupDepth levels.
std::vector<std::string> GroupSegments(const std::string& group);

// One group of one output's contributors.
struct GroupResult {
  std::string name;  // its last segment, "amplifier"
  std::string path;  // from the top, "stage/amplifier"
  int depth = 0;     // 0 for a top-level group
  double variance = 0.0;
  double share = 0.0;  // of the output's variance
  // Its direct members, in budget order: contributors (indices into
  // OutputResult::contributors) and the paths of its direct subgroups.
  std::vector<std::size_t> contributors;
  std::vector<std::string> subgroups;
  std::vector<double> band_variance;  // one per OutputResult::bands
  // Every contributor under it, at any depth (indices, budget order).
  std::vector<std::size_t> all_contributors;
};

// The groups of an output, depth first (each group before its subgroups),
// in the order their first contributor appears; none when no contributor
// names a group. Sums are over the contributors' stored figures.
std::vector<GroupResult> ComputeGroups(const OutputResult& output);

// The budget reduced to one sub-tree: the contributors in group `group` or
// below it (`deb run --group stage`).
// @throws InputError naming the groups there are (with the nearest) when no
//   contributor is in it.
Budget SelectGroup(const Budget& budget, const std::string& group);

}  // namespace deb
