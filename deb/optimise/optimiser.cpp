#include "deb/optimise/optimiser.h"

#include <nlopt.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include "deb/budget/engine.h"
#include "deb/budget/realisation_gradient.h"
#include "deb/core/byte_record.h"
#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/core/parallel.h"
#include "deb/core/suggest.h"
#include "deb/uncertainty/sample_design.h"
#include "deb/uncertainty/sample_statistics.h"

namespace deb {

namespace {

// The objective's value where the budget does not evaluate (relative to the
// nominal objective): far above any design that does.
constexpr double kFailedObjective = 1e3;
// A requirement within this of its limit at the optimum is active.
constexpr double kActive = 1e-3;

struct Evaluated {
  double objective = 0.0;  // unscaled; +inf when the budget failed
  std::vector<RequirementRatio> requirements;
  double worst = 0.0;
  std::string error;
};

// The budget's figures at one point (design values, then a sample's).
Evaluated EvaluatePoint(const DesignLoader& loader, const OptimiseObjective& objective,
                        const std::vector<double>& values) {
  Evaluated e;
  try {
    const BudgetResult r = Evaluate(loader(values), EngineOptions::VariancesOnly());
    e.requirements = RequirementRatios(r);
    for (const RequirementRatio& q : e.requirements) e.worst = std::max(e.worst, q.ratio());
    e.objective = objective.max_ratio ? e.worst : objective.Of(r);
  } catch (const InputError& error) {
    e.objective = std::numeric_limits<double>::infinity();
    e.worst = std::numeric_limits<double>::infinity();
    e.error = error.what();
  }
  return e;
}

// At a design: its figures, or (robust) their quantiles over the samples,
// the samples evaluated in parallel.
Evaluated EvaluateDesign(const DesignLoader& loader, const OptimiseObjective& objective,
                         const std::vector<double>& values, int threads = 1) {
  if (!objective.quantile) return EvaluatePoint(loader, objective, values);
  const std::size_t n = objective.samples.size();
  DEB_DEMAND(n >= 1);
  std::vector<Evaluated> at(n);
  ParallelForEach(
      n,
      [&](std::size_t s) {
        std::vector<double> v = values;
        v.insert(v.end(), objective.samples[s].begin(), objective.samples[s].end());
        at[s] = EvaluatePoint(loader, objective, v);
      },
      threads);
  for (const Evaluated& a : at)
    if (!a.error.empty()) return a;
  const double q = *objective.quantile;
  Evaluated e;
  e.requirements = at[0].requirements;
  for (std::size_t j = 0; j < e.requirements.size(); ++j) {
    std::vector<double> rms;
    for (const Evaluated& a : at) rms.push_back(a.requirements[j].rms);
    // A margin's bad tail is its low end: its (1 - q) quantile.
    e.requirements[j].rms = Percentile(rms, e.requirements[j].margin ? 1.0 - q : q);
    e.worst = std::max(e.worst, e.requirements[j].ratio());
  }
  if (objective.max_ratio) {
    e.objective = e.worst;
  } else {
    std::vector<double> f;
    for (const Evaluated& a : at) f.push_back(a.objective);
    e.objective = Percentile(f, q);
  }
  return e;
}

std::string StopText(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS: return "converged";
    case nlopt::STOPVAL_REACHED: return "objective reached its stop value";
    case nlopt::FTOL_REACHED: return "converged (objective tolerance)";
    case nlopt::XTOL_REACHED: return "converged (variables' tolerance)";
    case nlopt::MAXEVAL_REACHED: return "evaluation limit reached";
    case nlopt::MAXTIME_REACHED: return "time limit reached";
    case nlopt::ROUNDOFF_LIMITED: return "stopped by rounding (the optimum as good as rounding allows)";
    case nlopt::FORCED_STOP: return "stopped";
    default: return "failed (" + std::to_string(static_cast<int>(r)) + ")";
  }
}

// Where the gradients are exact (deb/budget/realisation_gradient.h): the
// objective is outputs' RMS at the designs themselves (not robust, not
// max-ratio), every requirement is an output's rms_max, and every variable
// acts on the budget only through rational paths' realisations (verified
// once, at the nominal design).
struct ExactGradientPlan {
  bool usable = false;
  std::string note;                          // the gradients' method, or why not exact
  std::vector<std::size_t> requirement_output;  // per requirement: its output
};

// Each variable's step of the realisation's derivative: 1e-3 of its range.
double RealisationStep(const DesignVariable& v) { return 1e-3 * (v.max - v.min); }

// The budgets at values with variable i moved by +h, -h, +h/2, -h/2, on the
// grid and bands of `at`.
std::array<Budget, 4> Stepped(const DesignLoader& loader, const std::vector<double>& values, std::size_t i, double h,
                              const BudgetResult& at, const Budget& budget) {
  const std::array<double, 4> steps = {h, -h, 0.5 * h, -0.5 * h};
  std::array<Budget, 4> out;
  for (std::size_t k = 0; k < 4; ++k) {
    std::vector<double> v = values;
    v[i] += steps[k];
    out[k] = loader(v);
    out[k].grid = ExplicitGrid(at.grid);
    if (out[k].bands.empty()) out[k].bands = budget.bands;
  }
  return out;
}

ExactGradientPlan PlanExactGradients(const std::vector<DesignVariable>& variables, const OptimiseObjective& objective,
                                     const DesignLoader& loader, const Budget& nominal_budget,
                                     const BudgetResult& nominal_result, int threads) {
  ExactGradientPlan plan;
  if (objective.quantile || objective.max_ratio) {
    plan.note = std::string("central differences: the objective is ") +
                (objective.quantile ? "a percentile under the tolerances" : "the largest requirement ratio");
    return plan;
  }
  for (std::size_t o = 0; o < nominal_result.outputs.size(); ++o) {
    const OutputResult& out = nominal_result.outputs[o];
    if (!out.band_requirements.empty()) {
      plan.note = "central differences: output " + out.name + " has band requirements";
      return plan;
    }
    if (out.rms_max) plan.requirement_output.push_back(o);
  }
  if (plan.requirement_output.size() != RequirementRatios(nominal_result).size()) {
    plan.note = "central differences: a loop's margin is required";
    return plan;
  }
  std::vector<double> nominal(variables.size());
  for (std::size_t i = 0; i < variables.size(); ++i) nominal[i] = variables[i].nominal;
  std::vector<std::string> refused(variables.size());
  ParallelForEach(
      variables.size(),
      [&](std::size_t i) {
        try {
          const RealisationGradient g =
              ComputeRealisationGradient(nominal_budget, nominal_result,
                                         Stepped(loader, nominal, i, RealisationStep(variables[i]), nominal_result,
                                                 nominal_budget),
                                         RealisationStep(variables[i]), EngineOptions::VariancesOnly());
          if (!g.exact) refused[i] = variables[i].name + ": " + g.note;
        } catch (const InputError& e) {
          refused[i] = variables[i].name + ": the budget fails a step away (" + e.what() + ")";
        }
      },
      threads);
  for (const std::string& why : refused)
    if (!why.empty()) {
      plan.note = "central differences: " + why;
      return plan;
    }
  plan.usable = true;
  plan.note = "exact: the derivative of the paths' realisations, propagated through H and the grid's integral";
  return plan;
}

// One start's search, in the variables scaled to [0, 1].
class Search {
 public:
  Search(const std::vector<DesignVariable>& variables, const OptimiseObjective& objective,
         const OptimiseOptions& options, const DesignLoader& loader, int start, double nominal_objective,
         std::size_t requirements, const ExactGradientPlan& exact)
      : variables_(variables), objective_(objective), options_(options), loader_(loader), start_(start),
        f0_(nominal_objective), m_(requirements), exact_(exact) {}

  std::vector<double> Values(const std::vector<double>& x) const {
    std::vector<double> v(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      v[i] = variables_[i].min + std::clamp(x[i], 0.0, 1.0) * (variables_[i].max - variables_[i].min);
    return v;
  }

  const Evaluated& At(const std::vector<double>& x) {
    const auto it = cache_.find(x);
    if (it != cache_.end()) return it->second;
    return Store(x, EvaluateDesign(loader_, objective_, Values(x), options_.threads));
  }

  // The objective and the constraints' gradients at x: exact where the plan
  // allows and the design and its steps evaluate, else by central
  // differences (one-sided at a bound), their 2n budgets evaluated in
  // parallel.
  void Gradients(const std::vector<double>& x, std::vector<double>* df, std::vector<std::vector<double>>* dg) {
    const auto it = gradients_.find(x);
    if (it != gradients_.end()) {
      *df = it->second.first;
      *dg = it->second.second;
      return;
    }
    if (!(exact_.usable && ExactGradients(x, df, dg))) CentralDifferences(x, df, dg);
    gradients_.emplace(x, std::make_pair(*df, *dg));
  }

  // d var / dv of every output from the realisations' derivatives, chained
  // to the scaled objective and the requirement ratios. False where the
  // design, a step of it, or a realisation's derivative fails.
  bool ExactGradients(const std::vector<double>& x, std::vector<double>* df, std::vector<std::vector<double>>* dg) {
    const std::size_t n = x.size();
    const std::vector<double> v = Values(x);
    Budget budget;
    BudgetResult at;
    try {
      budget = loader_(v);
      at = Evaluate(budget, EngineOptions::VariancesOnly());
    } catch (const InputError&) {
      return false;
    }
    // d var_o / dv_i, per variable.
    std::vector<std::vector<double>> dvar(n);
    std::vector<bool> ok(n, false);
    ParallelForEach(
        n,
        [&](std::size_t i) {
          try {
            const double h = RealisationStep(variables_[i]);
            const RealisationGradient g = ComputeRealisationGradient(
                budget, at, Stepped(loader_, v, i, h, at, budget), h, EngineOptions::VariancesOnly(), false);
            if (!g.exact) return;
            for (const std::vector<double>& per_contributor : g.d_variance) {
              double sum = 0.0;
              for (double d : per_contributor) sum += d;
              dvar[i].push_back(sum);
            }
            ok[i] = true;
          } catch (const InputError&) {
          }
        },
        options_.threads);
    for (bool b : ok)
      if (!b) return false;
    // d RMS / dx_i = d var / dv_i (max - min) / (2 RMS).
    const auto d_rms = [&](std::size_t o, std::size_t i) {
      const double rms = at.outputs[o].rms();
      return rms > 0.0 ? dvar[i][o] * (variables_[i].max - variables_[i].min) / (2.0 * rms) : 0.0;
    };
    std::vector<double> f(n, 0.0);
    std::vector<std::vector<double>> g(m_, std::vector<double>(n, 0.0));
    for (std::size_t i = 0; i < n; ++i) {
      for (const ObjectiveTerm& t : objective_.terms)
        for (std::size_t o = 0; o < at.outputs.size(); ++o)
          if (at.outputs[o].name == t.output) f[i] += t.weight * d_rms(o, i) / f0_;
      for (std::size_t j = 0; j < m_; ++j) {
        const std::size_t o = exact_.requirement_output[j];
        g[j][i] = d_rms(o, i) / *at.outputs[o].rms_max;
      }
    }
    *df = std::move(f);
    *dg = std::move(g);
    return true;
  }

  void CentralDifferences(const std::vector<double>& x, std::vector<double>* df, std::vector<std::vector<double>>* dg) {
    const std::size_t n = x.size();
    const double h = std::max(1e-6, 10.0 * options_.tolerance);
    std::vector<std::vector<double>> points(2 * n, x);
    std::vector<double> step(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double up = std::min(1.0, x[i] + h), down = std::max(0.0, x[i] - h);
      points[2 * i][i] = up;
      points[2 * i + 1][i] = down;
      step[i] = up - down;
    }
    std::vector<Evaluated> results(2 * n);
    std::vector<bool> cached(2 * n);
    for (std::size_t k = 0; k < 2 * n; ++k) cached[k] = cache_.count(points[k]) > 0;
    ParallelForEach(
        2 * n,
        [&](std::size_t k) {
          if (!cached[k]) results[k] = EvaluateDesign(loader_, objective_, Values(points[k]));
        },
        options_.threads);
    for (std::size_t k = 0; k < 2 * n; ++k) results[k] = cached[k] ? cache_.at(points[k]) : Store(points[k], results[k]);
    df->assign(n, 0.0);
    dg->assign(m_, std::vector<double>(n, 0.0));
    for (std::size_t i = 0; i < n; ++i) {
      const Evaluated &a = results[2 * i], &b = results[2 * i + 1];
      (*df)[i] = (Scaled(a) - Scaled(b)) / step[i];
      for (std::size_t j = 0; j < m_; ++j) (*dg)[j][i] = (Ratio(a, j) - Ratio(b, j)) / step[i];
    }
  }

  double Scaled(const Evaluated& e) const {
    return std::isfinite(e.objective) ? e.objective / f0_ : kFailedObjective;
  }
  double Ratio(const Evaluated& e, std::size_t j) const {
    return e.error.empty() && j < e.requirements.size() ? e.requirements[j].ratio() : kFailedObjective;
  }

  std::vector<DesignEvaluation> history;

 private:
  const Evaluated& Store(const std::vector<double>& x, Evaluated e) {
    DesignEvaluation d;
    d.start = start_;
    d.values = Values(x);
    d.objective = e.objective;
    d.worst_ratio = e.worst;
    d.error = e.error;
    history.push_back(d);
    return cache_.emplace(x, std::move(e)).first->second;
  }

  const std::vector<DesignVariable>& variables_;
  const OptimiseObjective& objective_;
  const OptimiseOptions& options_;
  const DesignLoader& loader_;
  int start_;
  double f0_;
  std::size_t m_;
  const ExactGradientPlan& exact_;
  std::map<std::vector<double>, Evaluated> cache_;
  std::map<std::vector<double>, std::pair<std::vector<double>, std::vector<std::vector<double>>>> gradients_;
};

double Objective(unsigned n, const double* x, double* grad, void* data) {
  auto* s = static_cast<Search*>(data);
  const std::vector<double> v(x, x + n);
  const double f = s->Scaled(s->At(v));
  if (grad) {
    std::vector<double> df;
    std::vector<std::vector<double>> dg;
    s->Gradients(v, &df, &dg);
    std::copy(df.begin(), df.end(), grad);
  }
  return f;
}

void Constraints(unsigned m, double* result, unsigned n, const double* x, double* grad, void* data) {
  auto* s = static_cast<Search*>(data);
  const std::vector<double> v(x, x + n);
  const Evaluated& e = s->At(v);
  for (unsigned j = 0; j < m; ++j) result[j] = s->Ratio(e, j) - 1.0;
  if (grad) {
    std::vector<double> df;
    std::vector<std::vector<double>> dg;
    s->Gradients(v, &df, &dg);
    for (unsigned j = 0; j < m; ++j)
      for (unsigned i = 0; i < n; ++i) grad[j * n + i] = dg[j][i];
  }
}

nlopt::algorithm AlgorithmOf(OptimiseMethod m) {
  switch (m) {
    case OptimiseMethod::kAuto:
    case OptimiseMethod::kCobyla: return nlopt::LN_COBYLA;
    case OptimiseMethod::kBobyqa: return nlopt::LN_BOBYQA;
    case OptimiseMethod::kSlsqp: return nlopt::LD_SLSQP;
    case OptimiseMethod::kMma: return nlopt::LD_MMA;
  }
  return nlopt::LN_COBYLA;
}

}  // namespace

std::string OptimiseObjective::Text() const {
  std::string what;
  if (max_ratio) {
    what = "the largest RMS / requirement";
  } else if (terms.size() == 1 && terms[0].weight == 1.0) {
    what = "the RMS of " + terms[0].output;
  } else {
    what = "the weighted sum";
    for (std::size_t i = 0; i < terms.size(); ++i)
      what += (i == 0 ? " " : " + ") + (terms[i].weight == 1.0 ? "" : SignificantText(terms[i].weight, 6) + " ") +
              "RMS(" + terms[i].output + ")";
  }
  if (!quantile) return what;
  return "the P" + SignificantText(100.0 * *quantile, 4) + " of " + what + " under the tolerances (" +
         std::to_string(samples.size()) + " samples)";
}

double OptimiseObjective::Of(const BudgetResult& result) const {
  double sum = 0.0;
  for (const ObjectiveTerm& t : terms) {
    const auto o = std::find_if(result.outputs.begin(), result.outputs.end(),
                                [&](const OutputResult& out) { return out.name == t.output; });
    if (o == result.outputs.end()) return std::numeric_limits<double>::quiet_NaN();
    sum += t.weight * o->rms();
  }
  return sum;
}

double RequirementRatio::ratio() const {
  if (!margin) return rms / limit;
  if (std::isnan(rms) || rms <= 0.0) return std::numeric_limits<double>::infinity();
  return std::isinf(rms) ? 0.0 : limit / rms;
}

std::vector<RequirementRatio> RequirementRatios(const BudgetResult& result) {
  std::vector<RequirementRatio> out;
  for (const OutputResult& o : result.outputs) {
    if (o.rms_max) out.push_back({o.name, o.rms(), *o.rms_max});
    for (const BandRequirementResult& b : o.band_requirements)
      out.push_back({o.name + "[" + SignificantText(b.requirement.lo_hz) + "-" + SignificantText(b.requirement.hi_hz) +
                         " Hz]",
                     b.rms(), b.requirement.rms_max});
  }
  for (const LoopResult& loop : result.loops)
    for (const MarginCheck& c : MarginChecks(loop)) {
      RequirementRatio q;
      q.name = "loop " + loop.plant + "/" + loop.controller + " " + c.what;
      q.rms = c.actual;
      q.limit = c.required;
      q.margin = true;
      out.push_back(q);
    }
  return out;
}

DesignMap MapDesigns(const std::vector<DesignVariable>& variables, const OptimiseObjective& objective,
                     const DesignLoader& loader, int n, int threads) {
  DEB_DEMAND(variables.size() == 2 && n >= 2);
  DesignMap map;
  const auto count = static_cast<std::size_t>(n);
  for (std::size_t k = 0; k < count; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(n - 1);
    map.x.push_back(variables[0].min + t * (variables[0].max - variables[0].min));
    map.y.push_back(variables[1].min + t * (variables[1].max - variables[1].min));
  }
  map.objective.assign(count, std::vector<double>(count));
  map.worst_ratio.assign(count, std::vector<double>(count));
  ParallelForEach(
      count * count,
      [&](std::size_t k) {
        const std::size_t i = k / count, j = k % count;
        const Evaluated e = EvaluateDesign(loader, objective, {map.x[i], map.y[j]});
        const double nan = std::numeric_limits<double>::quiet_NaN();
        map.objective[i][j] = e.error.empty() ? e.objective : nan;
        map.worst_ratio[i][j] = e.error.empty() ? e.worst : nan;
      },
      threads);
  return map;
}

OptimiseResult RunOptimise(const std::vector<DesignVariable>& variables, const OptimiseObjective& objective,
                           const OptimiseOptions& options, const DesignLoader& loader, const StartRunner& runner) {
  const std::size_t n = variables.size();
  DEB_DEMAND(n >= 1 && options.starts >= 1 && options.max_evaluations >= 1);
  for (const DesignVariable& v : variables) DEB_DEMAND(v.min < v.max);
  OptimiseResult result;
  result.variables = variables;
  result.objective = objective;
  result.options = options;

  // The nominal design: it must evaluate, and it fixes the requirements.
  std::vector<double> nominal(n);
  for (std::size_t i = 0; i < n; ++i) nominal[i] = variables[i].nominal;
  std::vector<double> nominal_point = nominal;
  if (objective.quantile) {
    DEB_DEMAND(!objective.samples.empty() && *objective.quantile > 0.0 && *objective.quantile < 1.0);
    nominal_point.insert(nominal_point.end(), objective.samples[0].begin(), objective.samples[0].end());
  }
  const Budget nominal_budget = loader(nominal_point);
  const BudgetResult nominal_result = Evaluate(nominal_budget, EngineOptions::VariancesOnly());
  result.nominal_requirements = RequirementRatios(nominal_result);
  const std::size_t m = objective.max_ratio ? 0 : result.nominal_requirements.size();
  if (objective.max_ratio && result.nominal_requirements.empty())
    throw InputError("the objective max-ratio needs requirements (rms_max or band requirements), and " +
                     nominal_budget.name + " has none");
  if (!objective.max_ratio) {
    DEB_DEMAND(!objective.terms.empty());
    std::vector<std::string> names;
    for (const OutputResult& o : nominal_result.outputs) names.push_back(o.name);
    for (const ObjectiveTerm& t : objective.terms) {
      DEB_DEMAND(t.weight > 0.0 && std::isfinite(t.weight));
      if (std::find(names.begin(), names.end(), t.output) == names.end()) {
        std::string list;
        for (const std::string& s : names) list += (list.empty() ? "" : ", ") + s;
        throw InputError("--objective " + t.output + ": no output of that name (the outputs: " + list +
                         "; or max-ratio)" + DidYouMean(t.output, names));
      }
    }
    result.nominal_objective = objective.Of(nominal_result);
  } else {
    for (const RequirementRatio& q : result.nominal_requirements)
      result.nominal_objective = std::max(result.nominal_objective, q.ratio());
  }
  if (objective.quantile) {
    // The nominal design under the tolerances: the robust objective's scale.
    const Evaluated e = EvaluateDesign(loader, objective, nominal, options.threads);
    if (!e.error.empty()) throw InputError("the nominal design under the tolerances: " + e.error);
    result.nominal_objective = e.objective;
    result.nominal_requirements = e.requirements;
  }
  result.method = options.method != OptimiseMethod::kAuto ? options.method
                  : m > 0                                  ? OptimiseMethod::kSlsqp
                                                           : OptimiseMethod::kBobyqa;
  if (m > 0 && options.method == OptimiseMethod::kBobyqa)
    throw InputError("--method bobyqa handles bounds only, and the budget has " + std::to_string(m) +
                     " requirement(s) to meet: use cobyla, slsqp or mma (or --objective max-ratio)");
  const double f0 = result.nominal_objective > 0.0 ? result.nominal_objective : 1.0;
  ExactGradientPlan exact;
  if (result.method == OptimiseMethod::kSlsqp || result.method == OptimiseMethod::kMma) {
    exact = PlanExactGradients(variables, objective, loader, nominal_budget, nominal_result, options.threads);
    result.gradients = exact.note;
  } else {
    result.gradients = "none (a derivative-free method)";
  }

  // The starts: the nominal design, then Sobol points of the box.
  const auto count = static_cast<std::size_t>(options.starts);
  const SampleDesign design(SamplingMethod::kSobol, options.seed, count + 1, n);
  std::vector<std::vector<double>> from(count);
  for (std::size_t k = 0; k < count; ++k) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i)
      x[i] = k == 0 ? std::clamp((nominal[i] - variables[i].min) / (variables[i].max - variables[i].min), 0.0, 1.0)
                    : design.Point(k)[i];
    from[k] = x;
  }
  const auto run = [&](std::size_t k) {
    Search search(variables, objective, options, loader, static_cast<int>(k), f0, m, exact);
    nlopt::opt opt(AlgorithmOf(result.method), static_cast<unsigned>(n));
    opt.set_lower_bounds(std::vector<double>(n, 0.0));
    opt.set_upper_bounds(std::vector<double>(n, 1.0));
    opt.set_min_objective(Objective, &search);
    if (m > 0) opt.add_inequality_mconstraint(Constraints, &search, std::vector<double>(m, 1e-9));
    opt.set_xtol_abs(options.tolerance);
    opt.set_maxeval(options.max_evaluations);
    if (result.method == OptimiseMethod::kCobyla || result.method == OptimiseMethod::kBobyqa)
      opt.set_initial_step(0.1);
    std::vector<double> x = from[k];
    double f = 0.0;
    std::string stop;
    try {
      stop = StopText(opt.optimize(x, f));
    } catch (const nlopt::roundoff_limited&) {
      stop = StopText(nlopt::ROUNDOFF_LIMITED);
    } catch (const std::runtime_error& e) {
      stop = std::string("NLopt failed: ") + e.what();
    }
    const Evaluated& at = search.At(x);
    StartOutcome out;
    OptimiseStart& s = out.start;
    s.from = search.Values(from[k]);
    s.values = search.Values(x);
    s.objective = at.objective;
    s.worst_ratio = at.worst;
    s.feasible = at.error.empty() && (m == 0 || at.worst <= 1.0 + 1e-6);
    s.stop = stop;
    out.requirements = at.requirements;
    out.history = std::move(search.history);
    s.evaluations = static_cast<int>(out.history.size());
    return out;
  };
  std::vector<StartOutcome> outcomes;
  if (runner) {
    outcomes = runner(count, run);
    if (outcomes.empty()) return result;  // a rank that does not write
    DEB_DEMAND(outcomes.size() == count);
  } else {
    outcomes.resize(count);
    ParallelForEach(count, [&](std::size_t k) { outcomes[k] = run(k); }, options.threads);
  }
  std::vector<OptimiseStart> starts(count);
  for (std::size_t k = 0; k < count; ++k) starts[k] = outcomes[k].start;

  // The best start: the lowest objective among the feasible, else the least
  // violating (ties: the earlier start).
  std::size_t best = 0;
  bool any = false;
  for (std::size_t k = 0; k < count; ++k) {
    const OptimiseStart& s = starts[k];
    if (s.feasible && (!any || s.objective < starts[best].objective)) {
      best = k;
      any = true;
    }
  }
  if (!any)
    for (std::size_t k = 1; k < count; ++k)
      if (starts[k].worst_ratio < starts[best].worst_ratio) best = k;
  result.starts = starts;
  result.best = best;
  result.feasible = any;
  result.requirements = outcomes[best].requirements;
  for (RequirementRatio& q : result.requirements) q.active = q.ratio() >= 1.0 - kActive;
  for (const StartOutcome& o : outcomes) {
    result.evaluations += static_cast<int>(o.history.size());
    result.history.insert(result.history.end(), o.history.begin(), o.history.end());
  }
  // A variable on its bound: the optimum with it a quarter of its range in.
  const std::vector<double>& optimum = starts[best].values;
  for (std::size_t i = 0; i < n; ++i) {
    const DesignVariable& v = variables[i];
    const double span = v.max - v.min, tolerance = 1e-6 * span;
    const bool at_min = optimum[i] <= v.min + tolerance, at_max = optimum[i] >= v.max - tolerance;
    if (!at_min && !at_max) continue;
    std::vector<double> moved = optimum;
    moved[i] = at_max ? v.max - 0.25 * span : v.min + 0.25 * span;
    const Evaluated e = EvaluateDesign(loader, objective, moved, options.threads);
    result.bound_probes.push_back({i, {-1, moved, e.objective, e.worst, e.error}});
  }
  return result;
}

namespace {

void PutRequirements(const std::vector<RequirementRatio>& list, ByteWriter* w) {
  w->Int(static_cast<std::int64_t>(list.size()));
  for (const RequirementRatio& q : list) {
    w->Text(q.name);
    w->Double(q.rms);
    w->Double(q.limit);
    w->Int(q.margin);
    w->Int(q.active);
  }
}

std::vector<RequirementRatio> GetRequirements(ByteReader* r, std::size_t record_bytes) {
  const std::int64_t n = r->Int();
  DEB_DEMAND(n >= 0 && static_cast<std::size_t>(n) <= record_bytes);  // each entry takes bytes
  std::vector<RequirementRatio> list(static_cast<std::size_t>(n));
  for (RequirementRatio& q : list) {
    q.name = r->Text();
    q.rms = r->Double();
    q.limit = r->Double();
    q.margin = r->Int() != 0;
    q.active = r->Int() != 0;
  }
  return list;
}

}  // namespace

std::string StartOutcomeToBytes(const StartOutcome& outcome) {
  ByteWriter w;
  const OptimiseStart& s = outcome.start;
  w.Doubles(s.from);
  w.Doubles(s.values);
  w.Double(s.objective);
  w.Double(s.worst_ratio);
  w.Int(s.feasible);
  w.Int(s.evaluations);
  w.Text(s.stop);
  w.Int(static_cast<std::int64_t>(outcome.history.size()));
  for (const DesignEvaluation& d : outcome.history) {
    w.Int(d.start);
    w.Doubles(d.values);
    w.Double(d.objective);
    w.Double(d.worst_ratio);
    w.Text(d.error);
  }
  PutRequirements(outcome.requirements, &w);
  return w.bytes();
}

StartOutcome StartOutcomeFromBytes(const std::string& bytes) {
  ByteReader r(bytes);
  StartOutcome outcome;
  OptimiseStart& s = outcome.start;
  s.from = r.Doubles();
  s.values = r.Doubles();
  s.objective = r.Double();
  s.worst_ratio = r.Double();
  s.feasible = r.Int() != 0;
  s.evaluations = static_cast<int>(r.Int());
  s.stop = r.Text();
  const std::int64_t n = r.Int();
  DEB_DEMAND(n >= 0 && static_cast<std::size_t>(n) <= bytes.size());  // each entry takes bytes
  outcome.history.resize(static_cast<std::size_t>(n));
  for (DesignEvaluation& d : outcome.history) {
    d.start = static_cast<int>(r.Int());
    d.values = r.Doubles();
    d.objective = r.Double();
    d.worst_ratio = r.Double();
    d.error = r.Text();
  }
  outcome.requirements = GetRequirements(&r, bytes.size());
  DEB_DEMAND(r.AtEnd());
  return outcome;
}

}  // namespace deb
