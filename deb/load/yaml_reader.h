// Internal: not part of the public API.
// The one place deb reads YAML. A YamlReader records the position of every
// node by its key path ("sources[1].spectrum.level") as it parses the
// document, so every error — from the loader or from later validation that
// only knows the key path — reads "file:line:col: key.path: what is wrong".
// Unknown keys are rejected. Internal to deb/load: not a public header.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/key_positions.h"
#include "deb/parameters/parameter_set.h"

namespace deb::load {

class YamlReader;

// A node together with its key path.
class YamlNode {
 public:
  YamlNode(const YamlReader* reader, YAML::Node node, std::string key);

  const std::string& key() const { return key_; }
  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }
  bool Has(const std::string& field) const;

  // Child of a map; Required throws when missing.
  YamlNode Required(const std::string& field) const;
  std::optional<YamlNode> Optional(const std::string& field) const;
  // Elements of a sequence. @throws InputError if this is not a sequence.
  std::vector<YamlNode> Elements() const;
  std::size_t size() const { return node_.size(); }
  // Keys of a map, in document order. @throws InputError if this is not a map.
  std::vector<std::string> Keys() const;

  // @throws InputError if this map has a key outside `allowed` (listed in the message).
  void AllowOnly(const std::set<std::string>& allowed) const;

  std::string AsString() const;
  // A finite number, written as one or as an expression (deb/parameters/
  // expression.h) of the budget's parameters. The field's unit comes from
  // its key: a key ending in _hz takes Hz, _s seconds, _deg degrees, and a
  // quantity with a unit is converted to it ("2 kHz" in f_hz is 2000); any
  // other number must be dimensionless (transfer-function coefficients,
  // matrices and gains are relative to their path's units, which a
  // quantity's SI value would silently ignore).
  double AsDouble() const;
  // A number in `unit` ("kg", "N/m"): a plain number is taken in it, a
  // quantity converted to it ("2.1 t" is 2100 in kg).
  double AsValueIn(const std::string& unit) const;
  double AsPositive() const;           // finite and > 0
  double AsNonNegative() const;        // finite and >= 0
  // The same in `unit`, as AsValueIn.
  double AsPositiveIn(const std::string& unit) const;
  double AsNonNegativeIn(const std::string& unit) const;
  int AsInt() const;
  bool AsBool() const;
  std::vector<double> AsDoubles() const;       // a scalar or a sequence of numbers
  std::vector<std::string> AsStrings() const;  // a scalar or a sequence of strings
  Eigen::MatrixXd AsMatrix() const;            // scalar (1x1), vector (1xn) or list of rows

  // An InputError located at this node.
  [[noreturn]] void Fail(const std::string& message) const;
  // The same, at byte `column` (1-based) of the node's text.
  [[noreturn]] void FailInText(int column, const std::string& message) const;
  // The same, at the node `at` (e.g. a map's key) under key path `key`.
  [[noreturn]] void FailAt(const YAML::Node& at, const std::string& key, const std::string& message) const;

 private:
  double EvaluateExpression(const std::string& text, const std::string& unit) const;
  const YamlReader* reader_;
  YAML::Node node_;
  std::string key_;
};

class YamlReader {
 public:
  // @throws InputError "file:line:col: ..." if the file cannot be read or parsed.
  static YamlReader FromFile(const std::string& path);
  static YamlReader FromString(const std::string& text, const std::string& name);
  // A document assembled from files each already read by FromFile (a budget
  // with `extends:`, budget_extends.h): its text, and the position of every
  // key path in the file that gave it.
  static YamlReader FromAssembled(const std::string& text, const std::string& name,
                                  std::shared_ptr<const KeyPositions> positions);
  // A document already parsed and checked (by FromFile or FromString) and
  // then changed by deb only (a sample of an uncertainty study): neither
  // parsed nor checked again; its errors are located by key path only, as
  // an assembled document's. Its text() is empty.
  static YamlReader FromChecked(YAML::Node root, const std::string& name);

  YamlNode Root() const;
  // True when the document is a map with key `field` (no error otherwise).
  bool RootHas(const std::string& field) const { return root_.IsMap() && root_[field].IsDefined(); }
  const std::string& name() const { return name_; }
  // The document's text, e.g. to load a copy to change (a sweep variant).
  const std::string& text() const { return text_; }
  // A fresh, changeable copy of the document (already checked when loaded).
  YAML::Node LoadCopy() const { return YAML::Load(text_); }

  // The position of every node of the document by key path, recorded as it
  // was parsed; shared with what is loaded from it (Budget::positions).
  const std::shared_ptr<const KeyPositions>& positions() const { return positions_; }
  // True for FromAssembled: the nodes' marks point into the assembled text,
  // which nobody wrote, so errors are located by key path only.
  bool assembled() const { return assembled_; }

  // The budget's parameters, which expressions in its numbers may use (none
  // until set).
  void SetParameters(std::shared_ptr<const ParameterSet> parameters) { parameters_ = std::move(parameters); }
  const ParameterSet& parameters() const;

 private:
  YamlReader(YAML::Node root, std::string name, std::string text, std::shared_ptr<const KeyPositions> positions);
  YAML::Node root_;
  std::string text_;
  std::string name_;
  std::shared_ptr<const KeyPositions> positions_;
  std::shared_ptr<const ParameterSet> parameters_;
  bool assembled_ = false;
};

// Runs f; an InputError it throws is re-thrown located at `node` (unless it
// has a place of its own: a key path or a file).
template <typename F>
auto AtNode(const YamlNode& node, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    if (e.located()) throw;
    node.Fail(e.message());
  }
}

// Runs f, which reports errors by key path (a library function given the
// nodes' keys): an InputError at the key of one of `nodes` is located at that
// node, one without a key path at `fallback`.
template <typename F>
auto AtNodes(const YamlNode& fallback, const std::vector<YamlNode>& nodes, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    for (const YamlNode& node : nodes)
      if (e.key_path() == node.key()) node.Fail(e.message());
    if (!e.key_path().empty()) throw;
    fallback.Fail(e.message());
  }
}

}  // namespace deb::load
