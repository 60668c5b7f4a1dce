#include "deb/uncertainty/uncertainty_study.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

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

UncertaintyResult RunUncertainty(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                 const VariantLoader& variant,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  const std::size_t p = spec.parameters.size();
  DEB_DEMAND(p >= 1 && options.samples >= 1 && options.samples <= kMaxUncertaintySamples);
  const Eigen::LLT<Eigen::MatrixXd> copula(spec.correlation.size() ? spec.correlation
                                                                   : Eigen::MatrixXd::Identity(p, p).eval());
  DEB_DEMAND(copula.info() == Eigen::Success);
  const bool sobol = options.method == SamplingMethod::kSobol;
  const std::size_t n = options.samples;
  const SampleDesign design(options.method, options.seed, n, sobol ? 2 * p : p);

  // The nominal budget and the gradient (central differences of 1 % of
  // each parameter's sigma), then the samples, then the corners: one list
  // of evaluations, run in parallel, stored by index.
  std::vector<double> nominal(p);
  for (std::size_t i = 0; i < p; ++i) nominal[i] = spec.parameters[i].nominal;
  std::vector<double> step(p);
  for (std::size_t i = 0; i < p; ++i) {
    const double sd = spec.parameters[i].distribution.StandardDeviation();
    step[i] = sd > 0.0 ? 0.01 * sd : 1e-6 * std::max(1.0, std::abs(nominal[i]));
  }
  const std::size_t per_base = sobol ? p + 2 : 1;
  const std::size_t sampled = n * per_base;
  const bool all_corners = p <= kMaxCornerParameters;
  const std::size_t corners = all_corners ? (std::size_t{1} << p) : 0;
  const std::size_t first_sample = 1 + 2 * p, first_corner = first_sample + sampled;
  const std::size_t total = first_corner + corners;

  std::vector<std::vector<double>> inputs(total), outputs(total);
  std::vector<double> low(p), high(p);
  for (std::size_t i = 0; i < p; ++i) {
    low[i] = spec.parameters[i].distribution.BoxLow();
    high[i] = spec.parameters[i].distribution.BoxHigh();
  }
  const auto input_of = [&](std::size_t e) -> std::vector<double> {
    if (e == 0) return nominal;
    if (e < first_sample) {
      std::vector<double> v = nominal;
      const std::size_t i = (e - 1) / 2;
      v[i] += (e - 1) % 2 == 0 ? step[i] : -step[i];
      return v;
    }
    if (e < first_corner) {
      const std::size_t j = (e - first_sample) / per_base, r = (e - first_sample) % per_base;
      const std::vector<double> u = design.Point(j);
      if (!sobol) return SampleValues(spec, copula, u);
      std::vector<double> a(u.begin(), u.begin() + static_cast<long>(p)), b(u.begin() + static_cast<long>(p), u.end());
      if (r == 1) return SampleValues(spec, copula, b);
      if (r >= 2) a[r - 2] = b[r - 2];
      return SampleValues(spec, copula, a);
    }
    const std::size_t vertex = e - first_corner;
    std::vector<double> v(p);
    for (std::size_t i = 0; i < p; ++i) v[i] = (vertex >> i) & 1 ? high[i] : low[i];
    return v;
  };
  const auto what_of = [&](std::size_t e) -> std::string {
    if (e == 0) return "the nominal budget";
    if (e < first_sample) return "the gradient's step of " + spec.parameters[(e - 1) / 2].name;
    if (e < first_corner) return "sample " + std::to_string((e - first_sample) / per_base + 1);
    return "corner " + std::to_string(e - first_corner + 1) + " of the tolerance box";
  };
  UncertaintyResult result;
  result.spec = spec;
  result.options = options;
  result.evaluations = total;
  {
    // The nominal budget first: it fixes the metrics every sample gives.
    inputs[0] = nominal;
    const BudgetResult r = Evaluate(variant(nominal), EngineOptions::VariancesOnly());
    result.metrics = MetricsOf(r);
    outputs[0] = MetricValues(r);
  }
  std::atomic<std::size_t> done{1};
  ParallelForEach(
      total - 1,
      [&](std::size_t j) {
        const std::size_t e = j + 1;
        inputs[e] = input_of(e);
        outputs[e] = EvaluateAt(variant, spec, inputs[e], what_of(e));
        const std::size_t d = ++done;
        if (progress) progress(d, total);
      },
      options.threads);

  const std::size_t m = result.metrics.size();
  for (std::size_t e = 0; e < total; ++e)
    if (outputs[e].size() != m)
      throw InputError(what_of(e) + " has " + std::to_string(outputs[e].size()) + " results where the nominal has " +
                       std::to_string(m));

  // The samples of the statistics: every one (mc, lhs); A and B (sobol).
  std::vector<std::size_t> stat;
  for (std::size_t j = 0; j < n; ++j) {
    stat.push_back(first_sample + j * per_base);
    if (sobol) stat.push_back(first_sample + j * per_base + 1);
  }
  result.samples = stat.size();
  result.parameter_values.assign(p, {});
  for (std::size_t i = 0; i < p; ++i)
    for (std::size_t e : stat) result.parameter_values[i].push_back(inputs[e][i]);

  std::vector<double> sd(p);
  for (std::size_t i = 0; i < p; ++i) sd[i] = spec.parameters[i].distribution.StandardDeviation();
  std::vector<bool> all_met(stat.size(), true);
  for (std::size_t k = 0; k < m; ++k) {
    StudyMetric& metric = result.metrics[k];
    metric.nominal = outputs[0][k];
    for (std::size_t e : stat) metric.values.push_back(outputs[e][k]);
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
      metric.gradient.push_back((outputs[1 + 2 * i][k] - outputs[2 + 2 * i][k]) / (2.0 * step[i]));
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
        fa.push_back(outputs[first_sample + j * per_base][k]);
        fb.push_back(outputs[first_sample + j * per_base + 1][k]);
      }
      for (std::size_t i = 0; i < p; ++i) {
        std::vector<double> fab;
        for (std::size_t j = 0; j < n; ++j) fab.push_back(outputs[first_sample + j * per_base + 2 + i][k]);
        metric.sobol.push_back(SobolIndicesOf(fa, fb, fab));
      }
    }
  }
  for (bool met : all_met) result.all_met += met ? 1 : 0;
  result.p_all_met = WilsonInterval(result.all_met, stat.size());

  // The worst corner of each metric: over every vertex (p <= 12), else the
  // vertex each parameter's rank correlation points to, evaluated here.
  if (all_corners) {
    result.corner_method = "all " + std::to_string(corners) + " vertices of the tolerance box";
    for (std::size_t k = 0; k < m; ++k) {
      std::size_t worst = first_corner;
      for (std::size_t e = first_corner; e < total; ++e)
        if (outputs[e][k] > outputs[worst][k]) worst = e;
      result.metrics[k].worst_corner = inputs[worst];
      result.metrics[k].worst_corner_value = outputs[worst][k];
    }
  } else {
    result.corner_method = "the vertex of the tolerance box each parameter's rank correlation points to (" +
                           std::to_string(p) + " parameters: 2^p vertices are too many to try)";
    std::vector<std::vector<double>> vertex(m, std::vector<double>(p));
    for (std::size_t k = 0; k < m; ++k)
      for (std::size_t i = 0; i < p; ++i) vertex[k][i] = result.metrics[k].spearman[i] >= 0.0 ? high[i] : low[i];
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

}  // namespace deb
