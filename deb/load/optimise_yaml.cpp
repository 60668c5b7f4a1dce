#include "deb/load/optimise_yaml.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/suggest.h"
#include "deb/load/design_bounds_yaml.h"
#include "deb/load/distributions_yaml.h"
#include "deb/load/parameter_variants.h"

namespace deb {

namespace {

std::string Trimmed(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

// "z_velocity + 0.5*x_velocity": terms split at '+', each OUTPUT or
// WEIGHT*OUTPUT with a finite weight > 0; the names are checked against the
// budget's outputs when it is evaluated (RunOptimise).
std::vector<ObjectiveTerm> ObjectiveTerms(const std::string& text) {
  const auto fail = [&](const std::string& term, const std::string& why) {
    return InputError("--objective '" + Excerpt(text) + "': term '" + Excerpt(term) + "': " + why +
                      " (give OUTPUT, or a weighted sum such as 'z + 0.5*x')");
  };
  std::vector<ObjectiveTerm> terms;
  std::size_t from = 0;
  while (true) {
    const std::size_t plus = text.find('+', from);
    const std::string term = Trimmed(text.substr(from, plus == std::string::npos ? std::string::npos : plus - from));
    ObjectiveTerm t;
    const std::size_t star = term.find('*');
    t.output = Trimmed(star == std::string::npos ? term : term.substr(star + 1));
    if (star != std::string::npos) {
      const std::string w = Trimmed(term.substr(0, star));
      char* end = nullptr;
      t.weight = std::strtod(w.c_str(), &end);
      if (w.empty() || end != w.c_str() + w.size()) throw fail(term, "weight '" + Excerpt(w) + "' is not a number");
      if (!(t.weight > 0.0) || !std::isfinite(t.weight))
        throw fail(term, "weight " + Excerpt(w) + " must be a finite number > 0");
    }
    if (t.output.empty()) throw fail(term, "no output named");
    if (t.output.find_first_of(" \t*") != std::string::npos) throw fail(term, "'" + Excerpt(t.output) + "' is not an output's name");
    for (const ObjectiveTerm& u : terms)
      if (u.output == t.output) throw fail(term, "output " + t.output + " appears twice; give it one weight");
    terms.push_back(t);
    if (terms.size() > kMaxObjectiveTerms) throw fail(term, "more than " + std::to_string(kMaxObjectiveTerms) + " terms");
    if (plus == std::string::npos) break;
    from = plus + 1;
  }
  return terms;
}

}  // namespace

std::vector<double> OptimiseBudget::Point(const std::vector<double>& design) const {
  std::vector<double> v = design;
  for (const UncertainParameter& p : uncertain.parameters) v.push_back(p.nominal);
  return v;
}

OptimiseObjective OptimiseBudget::Objective(const std::string& text, std::optional<double> percentile,
                                            std::size_t samples, std::uint64_t seed) const {
  OptimiseObjective o;
  if (text == "max-ratio") {
    o.max_ratio = true;
  } else if (!text.empty()) {
    o.terms = ObjectiveTerms(text);
  } else {
    std::vector<double> nominal;
    for (const DesignVariable& v : variables) nominal.push_back(v.nominal);
    const Budget b = loader(Point(nominal));
    if (b.outputs.size() == 1) o.terms = {{b.outputs.front().name, 1.0}};
    else o.max_ratio = true;
  }
  if (percentile) {
    DEB_DEMAND(*percentile > 0.0 && *percentile < 100.0 && !uncertain.parameters.empty());
    o.quantile = *percentile / 100.0;
    o.samples = LatinHypercubeValues(uncertain, samples, seed);
  }
  return o;
}

OptimiseBudget LoadOptimiseFile(const std::string& path, const std::vector<std::string>& vary,
                                const std::vector<BudgetOverride>& overrides, bool robust) {
  const load::StudyBudget budget = load::ReadStudyBudget(path, overrides);
  const std::vector<DesignVariable> bounded = load::ParseDesignBounds(budget.reader->Root(), *budget.parameters);
  OptimiseBudget out;
  out.name = budget.checked.name;
  if (vary.empty()) throw InputError(path + ": --vary: name the parameters to optimise (e.g. --vary Kv,h)");
  std::vector<std::string> with_bounds;
  for (const DesignVariable& v : bounded) with_bounds.push_back(v.name);
  for (const std::string& name : vary) {
    if (std::count(vary.begin(), vary.end(), name) > 1) throw InputError(path + ": --vary " + name + ": named twice");
    const auto it = std::find_if(bounded.begin(), bounded.end(), [&](const DesignVariable& v) { return v.name == name; });
    if (it != bounded.end()) {
      out.variables.push_back(*it);
      continue;
    }
    if (budget.parameters->Find(name) != nullptr)
      throw InputError(path + ": --vary " + name + ": the parameter has no bounds; give them in the budget, e.g. " +
                       name + ": {value: ..., min: ..., max: ...}" +
                       (with_bounds.empty() ? "" : " (parameters with bounds: " + [&] {
                         std::string list;
                         for (const std::string& s : with_bounds) list += (list.empty() ? "" : ", ") + s;
                         return list;
                       }() + ")"));
    throw InputError(path + ": --vary " + name + ": no parameter of that name" +
                     DidYouMean(name, budget.parameters->Names()));
  }
  std::vector<load::VariedParameter> varied;
  for (const DesignVariable& v : out.variables) varied.push_back({v.name, v.unit, v.unit_si});
  if (robust) {
    // The tolerances of the other parameters: a variable's own distribution
    // belongs to its nominal value, which the optimiser moves.
    const UncertaintySpec all = load::ParseUncertainty(budget.reader->Root(), *budget.parameters);
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < all.parameters.size(); ++i)
      if (std::find(vary.begin(), vary.end(), all.parameters[i].name) == vary.end()) kept.push_back(i);
    if (kept.empty())
      throw InputError(path + ": --robust: no parameter besides those of --vary has a distribution (the tolerances "
                       "the design must be robust to)");
    const auto k = static_cast<Eigen::Index>(kept.size());
    out.uncertain.correlation.resize(k, k);
    for (Eigen::Index a = 0; a < k; ++a) {
      out.uncertain.parameters.push_back(all.parameters[kept[static_cast<std::size_t>(a)]]);
      for (Eigen::Index b = 0; b < k; ++b)
        out.uncertain.correlation(a, b) = all.correlation(static_cast<Eigen::Index>(kept[static_cast<std::size_t>(a)]),
                                                          static_cast<Eigen::Index>(kept[static_cast<std::size_t>(b)]));
    }
    for (const UncertainParameter& p : out.uncertain.parameters) varied.push_back({p.name, p.unit, p.unit_si});
  }
  out.loader = load::ParameterVariants(budget, path, overrides, varied, "design");
  return out;
}

}  // namespace deb
