#include "deb/parameters/parameter_set.h"

#include <functional>
#include <map>

#include "deb/core/error.h"

namespace deb {
namespace {

bool IsReserved(const std::string& name) {
  static const char* const kReserved[] = {"pi",  "sqrt", "exp", "log", "log10", "sin",
                                          "cos", "tan",  "abs", "min", "max"};
  for (const char* r : kReserved)
    if (name == r) return true;
  return false;
}

}  // namespace

bool IsParameterName(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!letter(name[0])) return false;
  for (const char c : name)
    if (!letter(c) && !(c >= '0' && c <= '9')) return false;
  return !IsReserved(name);
}

ParameterSet ParameterSet::Evaluate(const std::vector<ParameterDefinition>& definitions) {
  if (definitions.size() > kMaxParameters) {
    throw InputError(definitions[kMaxParameters].key_path,
                     "more than " + std::to_string(kMaxParameters) + " parameters");
  }
  std::map<std::string, std::size_t> index;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < definitions.size(); ++i) {
    const ParameterDefinition& d = definitions[i];
    if (!IsParameterName(d.name)) {
      throw InputError(d.key_path, "'" + d.name.substr(0, 64) + "' is not a parameter name" +
                                       (IsReserved(d.name) ? " (it is a function or the constant pi)"
                                                           : " (a letter or _, then letters, digits or _; at most 64)"));
    }
    if (!index.emplace(d.name, i).second) {
      throw InputError(d.key_path, "parameter '" + d.name + "' is defined twice (first at " +
                                       definitions[index[d.name]].key_path + ")");
    }
    names.push_back(d.name);
  }
  std::vector<Expression> parsed;
  parsed.reserve(definitions.size());
  for (const ParameterDefinition& d : definitions) {
    try {
      parsed.push_back(Expression::Parse(d.expression));
    } catch (const ExpressionError& e) {
      throw e.At(d.key_path);
    }
    // A name no parameter has, before the order of evaluation is worked out
    // (found by the index; the error, with its suggestion, by the expression).
    for (const auto& used : parsed.back().names())
      if (!index.count(used.first)) {
        try {
          parsed.back().RequireKnownNames(names);
        } catch (const ExpressionError& e) {
          throw e.At(d.key_path);
        }
      }
  }

  // Depth-first, in definition order: each parameter after those it uses;
  // a parameter met again while on the path closes a cycle.
  ParameterSet set;
  std::vector<int> state(definitions.size(), 0);  // 0 new, 1 on the path, 2 done
  std::vector<Quantity> value(definitions.size());
  std::vector<std::size_t> path;
  const std::function<void(std::size_t)> visit = [&](std::size_t i) {
    if (state[i] == 2) return;
    if (state[i] == 1) {
      std::string cycle;
      std::size_t k = path.size();
      while (k > 0 && path[k - 1] != i) --k;
      for (std::size_t j = k - 1; j < path.size(); ++j) cycle += definitions[path[j]].name + " -> ";
      cycle += definitions[i].name;
      throw InputError(definitions[i].key_path, "parameters refer to each other in a cycle: " + cycle);
    }
    if (path.size() >= kMaxParameterDepth)
      throw InputError(definitions[i].key_path, "parameters refer to each other more than " +
                                                    std::to_string(kMaxParameterDepth) + " deep");
    state[i] = 1;
    path.push_back(i);
    for (const auto& used : parsed[i].names()) visit(index.at(used.first));
    path.pop_back();
    try {
      value[i] = parsed[i].Evaluate(
          [&](const std::string& name) -> const Quantity* {
            const auto it = index.find(name);
            return it == index.end() ? nullptr : &value[it->second];
          },
          names);
    } catch (const ExpressionError& e) {
      throw e.At(definitions[i].key_path);
    }
    state[i] = 2;
  };
  for (std::size_t i = 0; i < definitions.size(); ++i) visit(i);
  for (std::size_t i = 0; i < definitions.size(); ++i) {
    Parameter p;
    p.definition = definitions[i];
    p.value = value[i];
    p.derived = !parsed[i].IsLiteral();
    p.unit = parsed[i].LiteralUnit();
    if (!definitions[i].unit.empty()) {
      try {
        ValueIn(p.value, definitions[i].unit);
      } catch (const InputError& e) {
        throw InputError(definitions[i].key_path + ".unit", "'" + definitions[i].name + "' is " + Describe(p.value) +
                                                                 ", not a quantity in '" + definitions[i].unit +
                                                                 "' (" + e.message() + ")");
      }
      p.unit = definitions[i].unit;
    }
    set.parameters_.push_back(std::move(p));
  }
  set.index_ = std::move(index);
  return set;
}

const Quantity* ParameterSet::Find(const std::string& name) const {
  const auto it = index_.find(name);
  return it == index_.end() ? nullptr : &parameters_[it->second].value;
}

std::vector<std::string> ParameterSet::Names() const {
  std::vector<std::string> names;
  for (const Parameter& p : parameters_) names.push_back(p.definition.name);
  return names;
}

Quantity ParameterSet::EvaluateText(const std::string& text) const {
  return Expression::Parse(text).Evaluate([this](const std::string& name) { return Find(name); }, Names());
}

}  // namespace deb
