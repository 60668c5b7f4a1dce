// Internal: not part of the public API.
// Key paths into a budget's YAML, e.g. "paths[0].isolators[*].position[2]":
// the names deb's error messages give, and how a sweep, a sensitivity and
// `--set` change a budget file before it is loaded (so that every rule of
// the loader still applies to the changed budget). A segment is a map key
// with optional [i] (element i) or [*] (every element).
//
// The editing functions change the document in place and return "" or why
// the key path does not reach what they need ("sources[1] has no key 'levle',
// did you mean 'level'? (it has: ...)"). A YAML alias makes one node appear
// at several places: it is changed once, and nested aliases cannot make a
// short file a walk of more than limits::kMaxKeyPathVisits nodes.
#pragma once

#include <yaml-cpp/yaml.h>

#include <functional>
#include <string>
#include <vector>

namespace deb::load {

// One segment: a map key, or an index into a list (-1: every element).
struct KeyPathStep {
  std::string key;
  long index = 0;
  bool is_key = true;
};
using KeyPath = std::vector<KeyPathStep>;

// @throws InputError (unlocated) "key path 'a..b': empty key at character 3
//         (write e.g. paths[0].isolators[*].position[2])" for malformed text.
KeyPath ParseKeyPath(const std::string& text);

// A budget's parameter by its name alone: a path of one key that is not a
// top-level key of `root` but names one of its `parameters:` becomes
// parameters.NAME (parameters.NAME.value where it is given as a map).
// Any other path is returned as it is.
KeyPath ResolveParameterName(const YAML::Node& root, KeyPath path);

// Replaces every number x the path reaches (a number, or each element of a
// list of numbers) by scale(x).
std::string ScaleNumbersAt(YAML::Node root, const KeyPath& path, const std::function<double(double)>& scale);

// Multiplies every value the path reaches by `factor`: numbers and lists of
// numbers as ScaleNumbersAt, and an expression (a parameter's "5.2e4 N/m")
// as a whole, "(TEXT)*F"; `numbers` (if given) receives each number's value
// before, and NaN for an expression; `expressions` (if given) receives each
// expression's text, and "" for a number.
std::string MultiplyValuesAt(YAML::Node root, const KeyPath& path, double factor,
                             std::vector<double>* numbers = nullptr, std::vector<std::string>* expressions = nullptr);

// Writes `text` at every single value (scalar) the path reaches.
std::string SetTextAt(YAML::Node root, const KeyPath& path, const std::string& text);

// Replaces whatever the path reaches (a value, a list, a map) by a copy of
// `value`. The key must exist: a misspelt key is an error, not a new entry.
std::string ReplaceAt(YAML::Node root, const KeyPath& path, const YAML::Node& value);

}  // namespace deb::load
