#include "deb/results/optimise_files.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "deb/core/number_text.h"
#include "deb/version.h"

namespace deb {

using Json = nlohmann::ordered_json;

namespace {

double Shown(const DesignVariable& v, double si) { return si / v.unit_si; }

// A YAML single-quoted scalar: 'text', each ' doubled.
std::string YamlSingleQuoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  return quoted + "'";
}

// To 15 significant digits: the conversion from SI leaves the last of 17
// noisy (the bound 0.4 m read "399.99999999999994 mm"); 15 keep the value to
// 1e-15 of itself, below what any figure of a budget resolves.
std::string ValueText(const DesignVariable& v, double si) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.15g", Shown(v, si));
  return text + (v.unit.empty() ? std::string() : " " + v.unit);
}

Json Values(const OptimiseResult& r, const std::vector<double>& si) {
  Json j;
  for (std::size_t i = 0; i < r.variables.size(); ++i) j[r.variables[i].name] = Shown(r.variables[i], si[i]);
  return j;
}

Json Requirements(const std::vector<RequirementRatio>& list, bool active) {
  Json a = Json::array();
  for (const RequirementRatio& q : list) {
    const auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
    Json j = q.margin ? Json{{"name", q.name}, {"margin", number(q.rms)}, {"required", q.limit}, {"ratio", number(q.ratio())}}
                      : Json{{"name", q.name}, {"rms", q.rms}, {"limit", q.limit}, {"ratio", q.ratio()}};
    if (active) j["active"] = q.active;
    a.push_back(j);
  }
  return a;
}

}  // namespace

std::string OptimumText(const OptimiseResult& r) {
  std::string s;
  const OptimiseStart& best = r.starts[r.best];
  for (std::size_t i = 0; i < r.variables.size(); ++i)
    s += (i ? ", " : "") + r.variables[i].name + " = " + SignificantText(Shown(r.variables[i], best.values[i]), 6) +
         (r.variables[i].unit.empty() ? "" : " " + r.variables[i].unit);
  return s;
}

std::vector<std::size_t> VariablesAtBound(const OptimiseResult& r) {
  std::vector<std::size_t> at;
  for (const BoundProbe& p : r.bound_probes) at.push_back(p.variable);
  return at;
}

std::string BoundsText(const OptimiseResult& r) {
  if (r.bound_probes.empty()) return "";
  const OptimiseStart& best = r.starts[r.best];
  std::string s = "On a bound: ";
  bool all_flat = true;
  for (std::size_t k = 0; k < r.bound_probes.size(); ++k) {
    const BoundProbe& p = r.bound_probes[k];
    const DesignVariable& v = r.variables[p.variable];
    const bool upper = best.values[p.variable] >= 0.5 * (v.min + v.max);
    s += (k ? ", " : "") + v.name + " at its " + (upper ? "maximum " : "minimum ") + ValueText(v, upper ? v.max : v.min);
    // How much the bound decides: the optimum with the variable a quarter
    // of its range in. Within kFlatObjective and meeting every requirement,
    // the objective is nearly flat there (the thesis' h: 0.2 % from 225 to
    // 400 mm), and the bound is no reason to move the design to it.
    const DesignEvaluation& e = p.at;
    if (!std::isfinite(e.objective) || !(best.objective > 0.0)) {
      all_flat = false;
      continue;
    }
    const double worse = e.objective / best.objective - 1.0;
    const bool meets = r.requirements.empty() || e.worst_ratio <= 1.0;
    all_flat = all_flat && meets && worse < kFlatObjective;
    s += " (at " + SignificantText(Shown(v, e.values[p.variable]), 4) + (v.unit.empty() ? "" : " " + v.unit) +
         ", the others as they are, the objective is " + SignificantText(100.0 * std::fabs(worse), 2) + " % " +
         (worse >= 0.0 ? "worse" : "better") + (meets ? "" : " and a requirement fails") + ")";
  }
  if (all_flat)
    return s + ": nearly flat there; the bound, not a clear optimum, decides the value.";
  return s + ": the range given, not the budget, limits the optimum there (widen it to see further).";
}

std::string OptimiseSummaryJson(const std::string& budget_name, const OptimiseResult& r) {
  Json j;
  j["deb_version"] = DEB_VERSION;
  j["study"] = "optimise";
  j["budget"] = budget_name;
  j["objective"] = r.objective.Text();
  j["method"] = ToString(r.method);
  j["gradients"] = r.gradients;
  j["starts"] = r.options.starts;
  j["evaluations"] = r.evaluations;
  Json variables = Json::array();
  for (const DesignVariable& v : r.variables)
    variables.push_back({{"name", v.name},
                         {"unit", v.unit},
                         {"nominal", Shown(v, v.nominal)},
                         {"min", Shown(v, v.min)},
                         {"max", Shown(v, v.max)}});
  j["variables"] = variables;
  std::vector<double> nominal;
  for (const DesignVariable& v : r.variables) nominal.push_back(v.nominal);
  j["nominal"] = {{"values", Values(r, nominal)},
                  {"objective", r.nominal_objective},
                  {"requirements", Requirements(r.nominal_requirements, false)}};
  const OptimiseStart& best = r.starts[r.best];
  j["optimum"] = {{"feasible", r.feasible},
                  {"start", r.best + 1},
                  {"values", Values(r, best.values)},
                  {"objective", best.objective},
                  {"requirements", Requirements(r.requirements, true)}};
  Json at_bound = Json::array();  // variables whose optimum is their range's bound
  for (std::size_t i : VariablesAtBound(r)) at_bound.push_back(r.variables[i].name);
  j["optimum"]["at_bound"] = at_bound;
  Json starts = Json::array();
  for (std::size_t k = 0; k < r.starts.size(); ++k) {
    const OptimiseStart& s = r.starts[k];
    starts.push_back({{"start", k + 1},
                      {"from", Values(r, s.from)},
                      {"values", Values(r, s.values)},
                      {"objective", s.objective},
                      {"worst_ratio", s.worst_ratio},
                      {"feasible", s.feasible},
                      {"evaluations", s.evaluations},
                      {"stop", s.stop}});
  }
  j["starts_run"] = starts;
  return j.dump(2) + "\n";
}

std::string OptimiseHistoryCsv(const OptimiseResult& r) {
  std::string csv = "evaluation,start";
  for (const DesignVariable& v : r.variables) csv += "," + v.name + (v.unit.empty() ? "" : " [" + v.unit + "]");
  csv += ",objective,worst_ratio,error\n";
  for (std::size_t e = 0; e < r.history.size(); ++e) {
    const DesignEvaluation& d = r.history[e];
    csv += std::to_string(e + 1) + "," + std::to_string(d.start + 1);
    for (std::size_t i = 0; i < r.variables.size(); ++i) csv += "," + NumberText(Shown(r.variables[i], d.values[i]));
    csv += "," + NumberText(d.objective) + "," + NumberText(d.worst_ratio) + ",";
    if (!d.error.empty()) {
      std::string quoted = "\"";
      for (char c : d.error) quoted += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
      csv += quoted + "\"";
    }
    csv += "\n";
  }
  return csv;
}

std::string OptimumDescription(const OptimiseResult& r, const std::string& budget_description) {
  const OptimiseStart& best = r.starts[r.best];
  std::string d = "The optimum of deb optimise: " + OptimumText(r) + " (" + r.objective.Text() + " minimised: " +
                  SignificantText(best.objective, 4) + ", nominal " + SignificantText(r.nominal_objective, 4) + "); " +
                  (r.feasible ? "every requirement met." : "NO design met every requirement: the least violating.");
  if (const std::string bounds = BoundsText(r); !bounds.empty()) d += " " + bounds;
  if (!budget_description.empty()) d += " The budget it varies, as written (its nominal values): " + budget_description;
  return d;
}

std::string OptimumYaml(const std::string& extends, const std::string& budget_name, const OptimiseResult& r,
                        const std::vector<std::string>& overrides) {
  const OptimiseStart& best = r.starts[r.best];
  std::string y = "# The optimum of deb optimise (deb " + std::string(DEB_VERSION) + "): " + r.objective.Text() +
                  " minimised over " + std::to_string(r.variables.size()) + " parameter(s) in " +
                  std::to_string(r.evaluations) + " evaluations (" + ToString(r.method) + ", " +
                  std::to_string(r.options.starts) + " start(s)); " +
                  (r.feasible ? "every requirement met." : "NO design met every requirement: the least violating.") +
                  "\n";
  if (!overrides.empty()) {
    y += "# The study ran with";
    for (const std::string& o : overrides) y += " --set '" + o + "'";
    y += "; run this budget with them too.\n";
  }
  y += "extends: " + YamlSingleQuoted(extends) + "\nname: " + budget_name +
       "_optimum\ndescription: " + YamlSingleQuoted(OptimumDescription(r, "")) + "\nparameters:\n";
  for (std::size_t i = 0; i < r.variables.size(); ++i)
    y += "  " + r.variables[i].name + ": " + ValueText(r.variables[i], best.values[i]) + "\n";
  return y;
}

}  // namespace deb
