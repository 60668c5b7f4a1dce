#include "deb/uncertainty/uncertainty_study.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>
#include <tuple>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/core/parallel.h"

namespace deb {

namespace {

// The metrics of a result, in a fixed order: per output its total, its
// contributors, its band requirements.
std::vector<StudyMetric> MetricsOf(const BudgetResult& r) {
  std::vector<StudyMetric> metrics;
  for (const OutputResult& o : r.outputs) {
    StudyMetric total;
    total.output = o.name;
    total.unit = o.unit;
    total.limit = o.rms_max;
    metrics.push_back(total);
    for (const ContributorResult& c : o.contributors) {
      StudyMetric m;
      m.output = o.name;
      m.contributor = c.name;
      m.unit = o.unit;
      metrics.push_back(m);
    }
    for (const BandRequirementResult& b : o.band_requirements) {
      StudyMetric m;
      m.output = o.name;
      m.band = SignificantText(b.requirement.lo_hz) + "-" + SignificantText(b.requirement.hi_hz) + " Hz";
      m.unit = o.unit;
      m.limit = b.requirement.rms_max;
      metrics.push_back(m);
    }
  }
  return metrics;
}

std::vector<double> MetricValues(const BudgetResult& r) {
  std::vector<double> v;
  for (const OutputResult& o : r.outputs) {
    v.push_back(o.rms());
    for (const ContributorResult& c : o.contributors) v.push_back(std::sqrt(std::max(0.0, c.variance)));
    for (const BandRequirementResult& b : o.band_requirements) v.push_back(b.rms());
  }
  return v;
}

// "k_iso = 5.1e+04 N/m, zeta = 0.021": the values as the budget receives them.
std::string ValuesText(const UncertaintySpec& spec, const std::vector<double>& values) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i)
    s += (i ? ", " : "") + spec.parameters[i].name + " = " + SignificantText(values[i] / spec.parameters[i].unit_si, 6) +
         (spec.parameters[i].unit.empty() ? "" : " " + spec.parameters[i].unit);
  return s;
}

// Every evaluation's metric values in one block, evaluation after
// evaluation: 8 bytes a value, not a vector (and its heap block) per
// evaluation, whose freed blocks a long study's later allocations could not
// reuse.
class MetricTable {
 public:
  MetricTable(std::size_t rows, std::size_t columns) : columns_(columns), values_(rows * columns) {}
  std::size_t rows() const { return columns_ ? values_.size() / columns_ : 0; }
  std::size_t columns() const { return columns_; }
  double operator()(std::size_t e, std::size_t k) const { return values_[e * columns_ + k]; }
  void SetRow(std::size_t e, const std::vector<double>& row) {
    DEB_DEMAND(row.size() == columns_ && (e + 1) * columns_ <= values_.size());
    std::copy(row.begin(), row.end(), values_.begin() + static_cast<std::ptrdiff_t>(e * columns_));
  }

 private:
  std::size_t columns_;
  std::vector<double> values_;
};

// The metric values of the budget at `values`; errors name `what`.
std::vector<double> EvaluateAt(const VariantLoader& variant, const UncertaintySpec& spec,
                               const std::vector<double>& values, const std::string& what) {
  try {
    // The study runs budgets in parallel, each on one thread.
    return MetricValues(Evaluate(variant(values), EngineOptions::VariancesOnly()));
  } catch (const InputError& e) {
    // A loader's message names the values; the engine's may not.
    const std::string message = e.what();
    if (message.find(spec.parameters.front().name + " = ") != std::string::npos) throw InputError(what + ": " + message);
    throw InputError(what + " (" + ValuesText(spec, values) + "): " + message);
  }
}

}  // namespace

bool UncertaintySpec::Correlated() const {
  return correlation.size() > 0 && !correlation.isIdentity(0.0);
}

std::string StudyMetric::Name() const {
  if (!band.empty()) return output + "[" + band + "]";
  return contributor.empty() ? output : output + "." + contributor;
}

std::vector<double> SampleValues(const UncertaintySpec& spec, const Eigen::LLT<Eigen::MatrixXd>& copula,
                                 const std::vector<double>& u) {
  const std::size_t p = spec.parameters.size();
  DEB_DEMAND(u.size() == p);
  std::vector<double> w = u;
  if (spec.Correlated()) {
    Eigen::VectorXd z(static_cast<Eigen::Index>(p));
    for (std::size_t i = 0; i < p; ++i) z(static_cast<Eigen::Index>(i)) = StandardNormalQuantile(u[i]);
    const Eigen::VectorXd c = copula.matrixL() * z;
    for (std::size_t i = 0; i < p; ++i)
      w[i] = std::min(std::max(StandardNormalCdf(c(static_cast<Eigen::Index>(i))), 0x1.0p-60), 1.0 - 0x1.0p-53);
  }
  std::vector<double> values(p);
  for (std::size_t i = 0; i < p; ++i) values[i] = spec.parameters[i].distribution.Quantile(w[i]);
  return values;
}

std::vector<std::vector<double>> LatinHypercubeValues(const UncertaintySpec& spec, std::size_t n, std::uint64_t seed) {
  const std::size_t p = spec.parameters.size();
  DEB_DEMAND(n >= 1 && p >= 1);
  const SampleDesign design(SamplingMethod::kLatinHypercube, seed, n, p);
  const Eigen::LLT<Eigen::MatrixXd> copula(spec.correlation.size() ? spec.correlation
                                                                   : Eigen::MatrixXd::Identity(p, p).eval());
  std::vector<std::vector<double>> values;
  for (std::size_t k = 0; k < n; ++k) values.push_back(SampleValues(spec, copula, design.Point(k)));
  return values;
}

namespace {

// The study's evaluations, by index e: 0 the nominal budget, 1..2p the
// gradient's steps (central differences of 1 % of each parameter's sigma),
// then the samples (per_base budgets each), then the corners; each one's
// parameter values a function of (spec, options, e) alone.
class StudyPlan {
 public:
  // The sample design's dimensions: p, or 2 p for sobol (the A and B
  // matrices). @throws InputError where Boost's Sobol table has too few.
  static std::size_t DesignDimensions(const UncertaintySpec& spec, const UncertaintyOptions& options) {
    const std::size_t p = spec.parameters.size();
    if (options.method != SamplingMethod::kSobol) return p;
    if (2 * p > MaxSobolDimensions())
      throw InputError(std::to_string(p) + " uncertain parameters; --method sobol takes at most " +
                       std::to_string(MaxSobolDimensions() / 2));
    return 2 * p;
  }

  StudyPlan(const UncertaintySpec& spec, const UncertaintyOptions& options)
      : spec_(spec), p_(spec.parameters.size()),
        copula_(spec.correlation.size() ? spec.correlation : Eigen::MatrixXd::Identity(p_, p_).eval()),
        sobol_(options.method == SamplingMethod::kSobol), n_(options.samples),
        design_(options.method, options.seed, n_, DesignDimensions(spec, options)) {
    DEB_DEMAND(p_ >= 1 && n_ >= 1 && n_ <= kMaxUncertaintySamples);
    DEB_DEMAND(copula_.info() == Eigen::Success);
    nominal_.resize(p_);
    step_.resize(p_);
    low_.resize(p_);
    high_.resize(p_);
    for (std::size_t i = 0; i < p_; ++i) {
      const Distribution& d = spec.parameters[i].distribution;
      nominal_[i] = spec.parameters[i].nominal;
      const double sd = d.StandardDeviation();
      step_[i] = sd > 0.0 ? 0.01 * sd : 1e-6 * std::max(1.0, std::abs(nominal_[i]));
      low_[i] = d.BoxLow();
      high_[i] = d.BoxHigh();
    }
    per_base_ = sobol_ ? p_ + 2 : 1;
    all_corners_ = p_ <= kMaxCornerParameters;
    corners_ = all_corners_ ? (std::size_t{1} << p_) : 0;
    first_sample_ = 1 + 2 * p_;
    first_corner_ = first_sample_ + n_ * per_base_;
    total_ = first_corner_ + corners_;
  }

  std::size_t total() const { return total_; }

  std::vector<double> Input(std::size_t e) const {
    if (e == 0) return nominal_;
    if (e < first_sample_) {
      std::vector<double> v = nominal_;
      const std::size_t i = (e - 1) / 2;
      v[i] += (e - 1) % 2 == 0 ? step_[i] : -step_[i];
      return v;
    }
    if (e < first_corner_) {
      const std::size_t j = (e - first_sample_) / per_base_, r = (e - first_sample_) % per_base_;
      const std::vector<double> u = design_.Point(j);
      if (!sobol_) return SampleValues(spec_, copula_, u);
      std::vector<double> a(u.begin(), u.begin() + static_cast<long>(p_)), b(u.begin() + static_cast<long>(p_), u.end());
      if (r == 1) return SampleValues(spec_, copula_, b);
      if (r >= 2) a[r - 2] = b[r - 2];
      return SampleValues(spec_, copula_, a);
    }
    const std::size_t vertex = e - first_corner_;
    std::vector<double> v(p_);
    for (std::size_t i = 0; i < p_; ++i) v[i] = (vertex >> i) & 1 ? high_[i] : low_[i];
    return v;
  }

  std::string What(std::size_t e) const {
    if (e == 0) return "the nominal budget";
    if (e < first_sample_) return "the gradient's step of " + spec_.parameters[(e - 1) / 2].name;
    if (e < first_corner_) return "sample " + std::to_string((e - first_sample_) / per_base_ + 1);
    return "corner " + std::to_string(e - first_corner_ + 1) + " of the tolerance box";
  }

  // The statistics of the evaluations' metric values (outputs(e, k), every e),
  // the metrics named by the nominal budget's result.
  UncertaintyResult Summarise(const UncertaintyOptions& options, const VariantLoader& variant,
                              const BudgetResult& nominal_result, const MetricTable& outputs) const;

  // Evaluation e's values into `table`. @throws InputError naming the
  // evaluation where they are not the table's columns (a part's file edited).
  void Store(std::size_t e, const std::vector<double>& values, MetricTable* table) const {
    if (values.size() != table->columns())
      throw InputError(What(e) + " has " + std::to_string(values.size()) + " results where the nominal has " +
                       std::to_string(table->columns()));
    table->SetRow(e, values);
  }

 private:
  const UncertaintySpec& spec_;
  std::size_t p_;
  Eigen::LLT<Eigen::MatrixXd> copula_;
  bool sobol_;
  std::size_t n_;
  SampleDesign design_;
  std::vector<double> nominal_, step_, low_, high_;
  std::size_t per_base_ = 1, corners_ = 0, first_sample_ = 0, first_corner_ = 0, total_ = 0;
  bool all_corners_ = true;
};

UncertaintyResult StudyPlan::Summarise(const UncertaintyOptions& options, const VariantLoader& variant,
                                       const BudgetResult& nominal_result,
                                       const MetricTable& outputs) const {
  const UncertaintySpec& spec = spec_;
  const std::size_t p = p_, n = n_, per_base = per_base_, first_sample = first_sample_, first_corner = first_corner_;
  const std::size_t total = total_;
  const bool sobol = sobol_;
  DEB_DEMAND(outputs.rows() == total);
  UncertaintyResult result;
  result.spec = spec;
  result.options = options;
  result.evaluations = total;
  result.metrics = MetricsOf(nominal_result);
  const std::size_t m = result.metrics.size();
  DEB_DEMAND(outputs.columns() == m);

  // The samples of the statistics: every one (mc, lhs); A and B (sobol).
  std::vector<std::size_t> stat;
  for (std::size_t j = 0; j < n; ++j) {
    stat.push_back(first_sample + j * per_base);
    if (sobol) stat.push_back(first_sample + j * per_base + 1);
  }
  result.samples = stat.size();
  result.parameter_values.assign(p, {});
  for (std::vector<double>& v : result.parameter_values) v.reserve(stat.size());
  for (std::size_t e : stat) {
    const std::vector<double> input = Input(e);
    for (std::size_t i = 0; i < p; ++i) result.parameter_values[i].push_back(input[i]);
  }

  std::vector<double> sd(p);
  for (std::size_t i = 0; i < p; ++i) sd[i] = spec.parameters[i].distribution.StandardDeviation();
  std::vector<bool> all_met(stat.size(), true);
  for (std::size_t k = 0; k < m; ++k) {
    StudyMetric& metric = result.metrics[k];
    metric.nominal = outputs(0, k);
    metric.values.reserve(stat.size());  // exactly: a study of 10^5 samples keeps these
    for (std::size_t e : stat) metric.values.push_back(outputs(e, k));
    metric.moments = MeanAndSd(metric.values);
    metric.p5 = Percentile(metric.values, 0.05);
    metric.p50 = Percentile(metric.values, 0.50);
    metric.p95 = Percentile(metric.values, 0.95);
    metric.p99 = Percentile(metric.values, 0.99);
    if (metric.limit) {
      for (std::size_t s = 0; s < stat.size(); ++s) {
        const bool met = metric.values[s] <= *metric.limit;
        metric.met += met ? 1 : 0;
        all_met[s] = all_met[s] && met;
      }
      metric.p_meet = WilsonInterval(metric.met, stat.size());
    }
    // First order: sigma^2 = g^T C g, C the parameters' covariance.
    double variance = 0.0;
    for (std::size_t i = 0; i < p; ++i)
      metric.gradient.push_back((outputs(1 + 2 * i, k) - outputs(2 + 2 * i, k)) / (2.0 * step_[i]));
    for (std::size_t i = 0; i < p; ++i)
      for (std::size_t j = 0; j < p; ++j) {
        const double rho = spec.correlation.size() ? spec.correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j))
                                                   : (i == j ? 1.0 : 0.0);
        variance += metric.gradient[i] * metric.gradient[j] * rho * sd[i] * sd[j];
      }
    metric.fosm_sd = std::sqrt(std::max(0.0, variance));
    for (std::size_t i = 0; i < p; ++i)
      metric.spearman.push_back(stat.size() >= 2 ? SpearmanCorrelation(result.parameter_values[i], metric.values) : 0.0);
    if (sobol) {
      std::vector<double> fa, fb;
      for (std::size_t j = 0; j < n; ++j) {
        fa.push_back(outputs(first_sample + j * per_base, k));
        fb.push_back(outputs(first_sample + j * per_base + 1, k));
      }
      for (std::size_t i = 0; i < p; ++i) {
        std::vector<double> fab;
        for (std::size_t j = 0; j < n; ++j) fab.push_back(outputs(first_sample + j * per_base + 2 + i, k));
        metric.sobol.push_back(SobolIndicesOf(fa, fb, fab));
      }
    }
  }
  for (bool met : all_met) result.all_met += met ? 1 : 0;
  result.p_all_met = WilsonInterval(result.all_met, stat.size());

  // The worst corner of each metric: over every vertex (p <= 12), else the
  // vertex each parameter's rank correlation points to, evaluated here.
  if (all_corners_) {
    result.corner_method = "all " + std::to_string(corners_) + " vertices of the tolerance box";
    for (std::size_t k = 0; k < m; ++k) {
      std::size_t worst = first_corner;
      for (std::size_t e = first_corner; e < total; ++e)
        if (outputs(e, k) > outputs(worst, k)) worst = e;
      result.metrics[k].worst_corner = Input(worst);
      result.metrics[k].worst_corner_value = outputs(worst, k);
    }
  } else {
    result.corner_method = "the vertex of the tolerance box each parameter's rank correlation points to (" +
                           std::to_string(p) + " parameters: 2^p vertices are too many to try)";
    std::vector<std::vector<double>> vertex(m, std::vector<double>(p));
    for (std::size_t k = 0; k < m; ++k)
      for (std::size_t i = 0; i < p; ++i) vertex[k][i] = result.metrics[k].spearman[i] >= 0.0 ? high_[i] : low_[i];
    std::vector<std::vector<double>> values(m);
    ParallelForEach(
        m, [&](std::size_t k) { values[k] = EvaluateAt(variant, spec, vertex[k], "the worst corner of " + result.metrics[k].Name()); },
        options.threads);
    for (std::size_t k = 0; k < m; ++k) {
      result.metrics[k].worst_corner = vertex[k];
      result.metrics[k].worst_corner_value = values[k][k];
    }
    result.evaluations += m;
  }
  if (sobol && spec.Correlated())
    result.notes.push_back("Sobol indices assume independent parameters; with correlated ones they are not a "
                           "decomposition of the variance (read the rank correlations instead)");
  return result;
}

// Evaluates e in [begin, end), but for those below `from` (the nominal,
// which RunUncertainty evaluates first), in parallel, each handed to
// store(e, values).
void EvaluateRange(const StudyPlan& plan, const UncertaintySpec& spec, const VariantLoader& variant,
                   std::size_t begin, std::size_t end, std::size_t from, int threads,
                   const std::function<void(std::size_t, const std::vector<double>&)>& store,
                   const std::function<void(std::size_t, std::size_t)>& progress) {
  std::atomic<std::size_t> done{from - begin};
  const std::size_t all = end - begin;  // the progress' total, the ones done before included
  ParallelForEach(
      end - from,
      [&](std::size_t j) {
        const std::size_t e = from + j;
        store(e, EvaluateAt(variant, spec, plan.Input(e), plan.What(e)));
        const std::size_t d = ++done;
        if (progress) progress(d, all);
      },
      threads);
}

}  // namespace

std::size_t UncertaintyEvaluationCount(const UncertaintySpec& spec, const UncertaintyOptions& options) {
  return StudyPlan(spec, options).total();
}

std::vector<std::vector<double>> EvaluateUncertaintyRange(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                                          const VariantLoader& variant, std::size_t begin,
                                                          std::size_t end) {
  const StudyPlan plan(spec, options);
  DEB_DEMAND(begin < end && end <= plan.total());
  std::vector<std::vector<double>> values(end - begin);
  EvaluateRange(
      plan, spec, variant, begin, end, begin, options.threads,
      [&](std::size_t e, const std::vector<double>& v) { values[e - begin] = v; }, {});
  return values;
}

UncertaintyPart EvaluateUncertaintyPart(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                        const VariantLoader& variant, const StudyShard& shard,
                                        const std::function<void(std::size_t, std::size_t)>& progress) {
  const StudyPlan plan(spec, options);
  UncertaintyPart part;
  part.total = plan.total();
  std::tie(part.begin, part.end) = shard.Range(part.total);
  part.values.assign(part.end - part.begin, {});
  EvaluateRange(
      plan, spec, variant, part.begin, part.end, part.begin, options.threads,
      [&](std::size_t e, const std::vector<double>& v) { part.values[e - part.begin] = v; }, progress);
  return part;
}

UncertaintyResult SummariseUncertainty(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                       const VariantLoader& variant, const std::vector<std::vector<double>>& values) {
  const StudyPlan plan(spec, options);
  DEB_DEMAND(values.size() == plan.total());
  const BudgetResult nominal = Evaluate(variant(plan.Input(0)), EngineOptions::VariancesOnly());
  MetricTable table(values.size(), MetricValues(nominal).size());
  for (std::size_t e = 0; e < values.size(); ++e) plan.Store(e, values[e], &table);
  return plan.Summarise(options, variant, nominal, table);
}

UncertaintyResult RunUncertainty(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                 const VariantLoader& variant,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  const StudyPlan plan(spec, options);
  const std::size_t total = plan.total();
  // The nominal budget first: it fixes the metrics every sample gives.
  const BudgetResult nominal = Evaluate(variant(plan.Input(0)), EngineOptions::VariancesOnly());
  const std::vector<double> nominal_values = MetricValues(nominal);
  MetricTable outputs(total, nominal_values.size());
  outputs.SetRow(0, nominal_values);
  EvaluateRange(
      plan, spec, variant, 0, total, 1, options.threads,
      [&](std::size_t e, const std::vector<double>& v) { plan.Store(e, v, &outputs); }, progress);
  return plan.Summarise(options, variant, nominal, outputs);
}

}  // namespace deb
