// A budget's named parameters: quantities with units, literal ("2100 kg")
// or derived from others ("sqrt(4*k_iso/m)/(2*pi)"), evaluated in
// dependency order. Every number of a budget may be an expression of them
// (expression.h), and studies (--set, sweep, sensitivity) change them by
// name.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "deb/parameters/expression.h"
#include "deb/units/quantity.h"

namespace deb {

struct ParameterDefinition {
  std::string name;         // a name: a letter or _, then letters, digits, _
  std::string expression;   // its value: "2100 kg", "0.02", "sqrt(k/m)"
  std::string description;  // optional, for reports
  std::string key_path;     // where it is defined ("parameters.m"), for errors
  // Optional: the unit it is shown in ("N/m" for m*(2*pi*f)^2, which is
  // otherwise shown in SI base units, kg s-2); its value must be in it.
  std::string unit;
};

struct Parameter {
  ParameterDefinition definition;
  Quantity value;
  // Refers to other parameters (a formula, not a number with a unit).
  bool derived = false;
  // The unit it is shown in: definition.unit if given, else for a literal
  // the unit as written ("kg"; "" for a plain number).
  std::string unit;
};

// At most this many parameters in one budget, and chains of derived
// parameters at most this long.
inline constexpr std::size_t kMaxParameters = 10000;
inline constexpr std::size_t kMaxParameterDepth = 256;

class ParameterSet {
 public:
  ParameterSet() = default;

  // Parses and evaluates every definition, each after the ones it refers
  // to. @throws InputError located at the definition's key path: a name that
  // is not a name, is defined twice or is a function's or pi; an
  // ExpressionError (with its column) for a bad expression, an unknown name
  // (the nearest suggested) or a unit mismatch; a cycle, naming its members
  // in order; more than kMaxParameters; a definition's unit that its value
  // is not in (at key path "<key_path>.unit").
  static ParameterSet Evaluate(const std::vector<ParameterDefinition>& definitions);

  // The parameter's value, or nullptr if there is none by that name.
  const Quantity* Find(const std::string& name) const;
  // In the order defined.
  const std::vector<Parameter>& parameters() const { return parameters_; }
  std::vector<std::string> Names() const;
  bool empty() const { return parameters_.empty(); }

  // `text` evaluated with these parameters.
  // @throws ExpressionError as Expression::Parse and Evaluate.
  Quantity EvaluateText(const std::string& text) const;

 private:
  std::vector<Parameter> parameters_;
  std::map<std::string, std::size_t> index_;
};

// True for a valid parameter name (a letter or _, then letters, digits or
// _; not pi or a function's name).
bool IsParameterName(const std::string& name);

}  // namespace deb
