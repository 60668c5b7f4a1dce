// Internal: not part of the public API.
// A set of YAML nodes told apart by identity (YAML::Node::is), for walks
// that must reach a node once however many aliases lead to it. The node's
// position in the text groups them, so a lookup compares with the few nodes
// at one position; the position alone does not tell nodes apart (every value
// parsed from a --set text is at (0, 0, 0), as a budget's root is, and an
// alias shares its anchor's).
#pragma once

#include <yaml-cpp/yaml.h>

#include <map>
#include <tuple>
#include <vector>

namespace deb::load {

class YamlNodeSet {
 public:
  // False if `n` was inserted before.
  bool Insert(const YAML::Node& n) {
    const YAML::Mark m = n.Mark();
    std::vector<YAML::Node>& same = seen_[{m.pos, m.line, m.column}];
    for (const YAML::Node& s : same)
      if (s.is(n)) return false;
    same.push_back(n);
    return true;
  }

 private:
  std::map<std::tuple<int, int, int>, std::vector<YAML::Node>> seen_;
};

}  // namespace deb::load
