// Budgets that name data files: a matrix written as YAML, the first
// InputError of loading and evaluating a budget, and the check that it is
// located at a key. The helpers the suites of the file readers share.
#pragma once

#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <regex>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/load/budget_yaml.h"

namespace deb::test {

// YAML for m: [[a, b], [c, d]] with the shortest text that reads back exactly.
inline std::string MatrixYaml(const Eigen::MatrixXd& m) {
  std::string s = "[";
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    s += r ? ", [" : "[";
    for (Eigen::Index c = 0; c < m.cols(); ++c) s += (c ? ", " : "") + NumberText(m(r, c));
    s += "]";
  }
  return s + "]";
}

// The message of the InputError that loading the budget `file`, or else
// evaluating it, throws; "(no InputError)" if none.
inline std::string ErrorOfBudget(const std::string& file) {
  Budget b;
  try {
    b = LoadBudgetFile(file);
  } catch (const InputError& e) {
    return e.what();
  }
  try {
    Evaluate(b);
  } catch (const InputError& e) {
    return e.what();  // located by the budget loaded
  }
  return "(no InputError)";
}

// "…/b.yaml:LINE:COL: KEY: …" and the rest of the message.
inline void CheckLocated(const std::string& message, const std::string& key, const std::string& part) {
  CAPTURE(message);
  CHECK(std::regex_search(message, std::regex("b\\.yaml:[0-9]+:[0-9]+: " +
                                              std::regex_replace(key, std::regex("[\\[\\].]"), "\\$&") + ": ")));
  CHECK(message.find(part) != std::string::npos);
}

}  // namespace deb::test
