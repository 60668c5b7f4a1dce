#include "deb/load/key_path.h"

#include <cstdio>
#include <limits>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/suggest.h"
#include "deb/load/yaml_node_set.h"

namespace deb::load {
namespace {

// The nodes a walk has reached (through aliases, a node is reached more than
// once), by identity (yaml_node_set.h).
class Reached {
 public:
  // False if n was reached before. Counts every call against the limit.
  bool First(const YAML::Node& n) {
    if (++calls_ > limits::kMaxKeyPathVisits) throw Overflow();
    return seen_.Insert(n);
  }
  struct Overflow {};
  static std::string Why() {
    return "the key path reaches more than " + std::to_string(limits::kMaxKeyPathVisits) +
           " values (nested YAML aliases?)";
  }

 private:
  std::size_t calls_ = 0;
  YamlNodeSet seen_;
};

std::string Text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool IsNumber(const YAML::Node& n) {
  if (!n.IsScalar()) return false;
  double d;
  return YAML::convert<double>::decode(n, d);
}

// Why map n at `where` has no `key`: the keys it has, the nearest first.
std::string NoKey(const YAML::Node& n, const std::string& key, const std::string& where) {
  std::vector<std::string> keys;
  std::string list;
  for (const auto& kv : n) {
    keys.push_back(kv.first.Scalar());  // plain scalars: the reader's document check
    list += (list.empty() ? "" : ", ") + keys.back();
  }
  return (where.empty() ? std::string("the budget") : where) + " has no key '" + key + "'" + DidYouMean(key, keys) +
         " (it has: " + list + ")";
}

// A number, or each number of a list of numbers, replaced by scale(x).
std::string ScaleLeaf(YAML::Node n, const std::string& where, Reached& reached,
                      const std::function<double(double)>& scale) {
  if (IsNumber(n)) {
    n = Text(scale(n.as<double>()));
    return "";
  }
  if (n.IsSequence() && n.size() > 0) {
    for (std::size_t k = 0; k < n.size(); ++k)
      if (!IsNumber(n[k])) return where + " is a list that holds something other than numbers";
    for (std::size_t k = 0; k < n.size(); ++k)
      if (reached.First(n[k])) n[k] = Text(scale(n[k].as<double>()));
    return "";
  }
  return where + " is not a number or a list of numbers";
}

// What to do with each node the path reaches (and its key path): "" or why not.
using Leaf = std::function<std::string(YAML::Node, const std::string& where, Reached&)>;

std::string Walk(YAML::Node n, const KeyPath& steps, std::size_t s, const std::string& where, Reached& reached,
                 const Leaf& leaf) {
  if (!reached.First(n)) return "";
  if (s == steps.size()) return leaf(n, where, reached);
  const KeyPathStep& step = steps[s];
  if (step.is_key) {
    if (!n.IsMap()) return (where.empty() ? std::string("the budget") : where) + " is not a map, so it has no key '" +
                           step.key + "'";
    const YAML::Node& cn = n;
    if (!cn[step.key]) return NoKey(n, step.key, where);
    return Walk(n[step.key], steps, s + 1, where.empty() ? step.key : where + "." + step.key, reached, leaf);
  }
  const std::string index = step.index < 0 ? std::string("*") : std::to_string(step.index);
  if (!n.IsSequence()) return where + " is not a list, so it has no element [" + index + "]";
  if (step.index >= 0) {
    if (static_cast<std::size_t>(step.index) >= n.size())
      return where + " has " + std::to_string(n.size()) + " element(s), so no [" + index + "]";
    return Walk(n[static_cast<std::size_t>(step.index)], steps, s + 1, where + "[" + index + "]", reached, leaf);
  }
  if (n.size() == 0) return where + " is an empty list: [*] reaches nothing";
  for (std::size_t k = 0; k < n.size(); ++k) {
    const std::string why = Walk(n[k], steps, s + 1, where + "[" + std::to_string(k) + "]", reached, leaf);
    if (!why.empty()) return why;
  }
  return "";
}

std::string WalkFromRoot(YAML::Node root, const KeyPath& path, const Leaf& leaf) {
  Reached reached;
  try {
    return Walk(root, path, 0, "", reached, leaf);
  } catch (const Reached::Overflow&) {
    return Reached::Why();
  }
}

}  // namespace

KeyPath ResolveParameterName(const YAML::Node& root, KeyPath path) {
  if (path.size() != 1 || !path[0].is_key || !root.IsMap()) return path;
  const std::string& name = path[0].key;
  if (root[name]) return path;  // a top-level key: the budget's own
  const YAML::Node parameters = root["parameters"];
  if (!parameters || !parameters.IsMap() || !parameters[name]) return path;
  KeyPath resolved{{"parameters", 0, true}, {name, 0, true}};
  if (parameters[name].IsMap()) resolved.push_back({"value", 0, true});
  return resolved;
}

std::string MultiplyValuesAt(YAML::Node root, const KeyPath& path, double factor, std::vector<double>* numbers,
                             std::vector<std::string>* expressions) {
  return WalkFromRoot(root, path, [&](YAML::Node n, const std::string& where, Reached& reached) -> std::string {
    if (n.IsScalar() && !IsNumber(n)) {
      // An expression: "(TEXT)*F" (a number and a unit stay one quantity).
      if (numbers) numbers->push_back(std::numeric_limits<double>::quiet_NaN());
      if (expressions) expressions->push_back(n.Scalar());
      n = "(" + n.Scalar() + ")*" + Text(factor);
      return "";
    }
    return ScaleLeaf(n, where, reached, [&](double x) {
      if (numbers) numbers->push_back(x);
      if (expressions) expressions->push_back("");
      return x * factor;
    });
  });
}

KeyPath ParseKeyPath(const std::string& text) {
  KeyPath steps;
  std::size_t i = 0;
  auto fail = [&](const std::string& why) {
    throw InputError("key path '" + text + "': " + why + " (write e.g. paths[0].isolators[*].position[2])");
  };
  while (i < text.size()) {
    std::string key;
    while (i < text.size() && text[i] != '.' && text[i] != '[') key += text[i++];
    if (key.empty()) fail("empty key at character " + std::to_string(i + 1));
    steps.push_back({key, 0, true});
    while (i < text.size() && text[i] == '[') {
      const std::size_t close = text.find(']', i);
      if (close == std::string::npos) fail("'[' without ']'");
      const std::string inside = text.substr(i + 1, close - i - 1);
      if (inside == "*") {
        steps.push_back({"", -1, false});
      } else {
        if (inside.empty() || inside.find_first_not_of("0123456789") != std::string::npos)
          fail("index '" + inside + "' is neither a number nor *");
        if (inside.size() > 9) fail("index " + inside + " is too large (at most 999999999)");
        steps.push_back({"", std::stol(inside), false});
      }
      i = close + 1;
    }
    if (i < text.size()) {
      if (text[i] != '.') fail("unexpected '" + std::string(1, text[i]) + "'");
      ++i;
      if (i == text.size()) fail("ends with '.'");
    }
  }
  if (steps.empty()) fail("empty");
  return steps;
}

std::string ScaleNumbersAt(YAML::Node root, const KeyPath& path, const std::function<double(double)>& scale) {
  return WalkFromRoot(root, path, [&](YAML::Node n, const std::string& where, Reached& reached) {
    return ScaleLeaf(n, where, reached, scale);
  });
}

std::string SetTextAt(YAML::Node root, const KeyPath& path, const std::string& text) {
  return WalkFromRoot(root, path, [&](YAML::Node n, const std::string& where, Reached&) -> std::string {
    if (!n.IsScalar()) return where + " is not a single value";
    n = text;
    return "";
  });
}

std::string ReplaceAt(YAML::Node root, const KeyPath& path, const YAML::Node& value) {
  return WalkFromRoot(root, path, [&](YAML::Node n, const std::string&, Reached&) -> std::string {
    n = YAML::Clone(value);
    return "";
  });
}

}  // namespace deb::load
