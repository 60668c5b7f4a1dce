#include "deb/budget/groups.h"

#include <algorithm>
#include <functional>
#include <map>

#include "deb/core/file_name.h"
#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/suggest.h"

namespace deb {
namespace {

bool GroupCharacter(char c) { return IsFileNameCharacter(c) || c == ' '; }

// True when `path` is `group` or lies below it.
bool Within(const std::string& path, const std::string& group) {
  return path == group || (path.size() > group.size() && path.compare(0, group.size(), group) == 0 &&
                           path[group.size()] == '/');
}

}  // namespace

std::vector<std::string> GroupSegments(const std::string& group) {
  std::vector<std::string> segments;
  std::string current;
  const auto fail = [&](const std::string& why) {
    throw InputError("group '" + group + "': " + why + " (write e.g. stage/amplifier)");
  };
  for (std::size_t i = 0; i <= group.size(); ++i) {
    if (i == group.size() || group[i] == '/') {
      if (current.empty()) fail("an empty name between '/'");
      if (current == "total") fail("'total' is reserved for the sum of all contributors");
      if (current.front() == ' ' || current.back() == ' ') fail("a name starts or ends with a space");
      segments.push_back(current);
      current.clear();
      continue;
    }
    if (!GroupCharacter(group[i])) {
      // The whole character (up to 4 bytes of UTF-8), not its first byte.
      const unsigned char lead = static_cast<unsigned char>(group[i]);
      const std::size_t bytes = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
      fail("character '" + Excerpt(group.substr(i, bytes), bytes) +
           "' is not allowed (letters, digits, _ - . and space)");
    }
    current += group[i];
  }
  if (segments.size() > kMaxGroupDepth)
    fail(std::to_string(segments.size()) + " levels, more than " + std::to_string(kMaxGroupDepth));
  return segments;
}

std::vector<GroupResult> ComputeGroups(const OutputResult& output) {
  std::vector<GroupResult> groups;
  std::map<std::string, std::size_t> index;  // path -> position in groups
  // Creates the groups along a path, parents first; returns the deepest.
  const auto ensure = [&](const std::string& path) {
    const std::vector<std::string> segments = GroupSegments(path);
    std::string so_far;
    std::size_t at = 0;
    for (std::size_t d = 0; d < segments.size(); ++d) {
      const std::string parent = so_far;
      so_far += (d ? "/" : "") + segments[d];
      auto it = index.find(so_far);
      if (it == index.end()) {
        GroupResult g;
        g.name = segments[d];
        g.path = so_far;
        g.depth = static_cast<int>(d);
        g.band_variance.assign(output.bands.size(), 0.0);
        groups.push_back(std::move(g));
        it = index.emplace(so_far, groups.size() - 1).first;
        if (d > 0) groups[index.at(parent)].subgroups.push_back(so_far);
      }
      at = it->second;
    }
    return at;
  };
  for (std::size_t c = 0; c < output.contributors.size(); ++c) {
    const ContributorResult& cr = output.contributors[c];
    if (cr.group.empty()) continue;
    groups[ensure(cr.group)].contributors.push_back(c);
    for (GroupResult& g : groups) {
      if (!Within(cr.group, g.path)) continue;
      g.all_contributors.push_back(c);
      g.variance += cr.variance;
      for (std::size_t b = 0; b < output.bands.size(); ++b)
        g.band_variance[b] += output.bands[b].contributor_variance[c];
    }
  }
  for (GroupResult& g : groups) g.share = output.variance > 0.0 ? g.variance / output.variance : 0.0;
  // Depth first: each group followed by its subtree, top-level groups in order of appearance.
  std::vector<GroupResult> ordered;
  const std::function<void(std::size_t)> visit = [&](std::size_t i) {
    ordered.push_back(groups[i]);
    for (const std::string& sub : groups[i].subgroups) visit(index.at(sub));
  };
  for (std::size_t i = 0; i < groups.size(); ++i)
    if (groups[i].depth == 0) visit(i);
  return ordered;
}

Budget SelectGroup(const Budget& budget, const std::string& group) {
  GroupSegments(group);  // a malformed name is said as such
  Budget b = budget;
  b.contributors.clear();
  std::vector<std::string> known;
  for (const Contributor& c : budget.contributors) {
    if (!c.group.empty()) {
      std::string so_far;
      for (const std::string& s : GroupSegments(c.group)) {
        so_far += (so_far.empty() ? "" : "/") + s;
        if (std::find(known.begin(), known.end(), so_far) == known.end()) known.push_back(so_far);
      }
    }
    if (!c.group.empty() && Within(c.group, group)) b.contributors.push_back(c);
  }
  if (b.contributors.empty()) {
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    throw InputError("no contributor is in group '" + group + "'" + DidYouMean(group, known) +
                     (known.empty() ? std::string(" (no contributor names a group)") : " (the groups: " + list + ")"));
  }
  return b;
}

}  // namespace deb
