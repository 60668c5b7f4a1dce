// An uncertainty study of a budget (deb uncertainty): its uncertain
// parameters sampled from their distributions, every sample's budget
// evaluated, and per output, contributor and band requirement the
// distribution of the RMS: mean, sigma, percentiles, P(meet) of each
// requirement with its Wilson interval, the drivers (Spearman rank
// correlations; Sobol indices with the sobol method), the first-order
// (FOSM) sigma from the gradient, and the worst corner of the tolerance box.
//
// Correlated parameters are sampled through a Gaussian copula: the design's
// uniforms u become normals z = Phi^-1(u), correlated as L z (L L^T the
// correlation matrix), back to uniforms Phi(L z), and each through its own
// distribution's quantile. A sample's values depend on (seed, index) only
// (sample_design.h); the statistics are computed from the table of samples
// in index order, so the result is the same for any thread count.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/result.h"
#include "deb/core/study_shard.h"
#include "deb/uncertainty/distribution.h"
#include "deb/uncertainty/sample_design.h"
#include "deb/uncertainty/sample_statistics.h"

namespace deb {

struct UncertainParameter {
  std::string name;        // the budget parameter's
  std::string unit;        // the unit it is written and shown in ("N/m"); "" for a plain number
  double unit_si = 1.0;    // one `unit` in coherent SI units
  double nominal = 0.0;    // the budget's value, SI
  Distribution distribution;  // of the SI value
};

struct UncertaintySpec {
  std::vector<UncertainParameter> parameters;
  // p x p, symmetric positive definite with unit diagonal; identity when
  // the budget gives no correlations.
  Eigen::MatrixXd correlation;
  bool Correlated() const;
};

// The most samples a study may take, and the most parameters whose corners
// are all evaluated (2^p budgets).
inline constexpr std::size_t kMaxUncertaintySamples = 1000000;
inline constexpr std::size_t kMaxCornerParameters = 12;

struct UncertaintyOptions {
  std::size_t samples = 1000;  // with sobol: N base samples, N (p + 2) budgets
  SamplingMethod method = SamplingMethod::kMonteCarlo;
  std::uint64_t seed = 1;
  int threads = 0;  // <= 0: all cores
};

// One quantity followed over the samples: an output's RMS, a contributor's,
// or an output's RMS within a band requirement.
struct StudyMetric {
  std::string output;
  std::string contributor;  // empty: the output's total
  std::string band;         // "10-100 Hz" for a band requirement; else empty
  std::string unit;
  std::optional<double> limit;  // the requirement's RMS limit, if it has one
  std::string Name() const;     // "z", "z.floor", "z[10-100 Hz]"

  std::vector<double> values;  // per sample (RMS)
  double nominal = 0.0;        // at the budget's own values
  Moments moments;
  double p5 = 0.0, p50 = 0.0, p95 = 0.0, p99 = 0.0;
  std::size_t met = 0;  // samples meeting the limit
  Interval p_meet;      // its 95 % Wilson interval
  double fosm_sd = 0.0;                // first-order sigma from the gradient
  std::vector<double> gradient;        // d RMS / d parameter (SI), per parameter
  std::vector<double> spearman;        // per parameter
  std::vector<SobolIndices> sobol;     // per parameter (sobol method only)
  // The tolerance box's vertex with the largest value, and that value.
  std::vector<double> worst_corner;  // SI, per parameter
  double worst_corner_value = 0.0;
};

struct UncertaintyResult {
  UncertaintySpec spec;
  UncertaintyOptions options;
  std::size_t samples = 0;      // in the statistics (2 N with sobol)
  std::size_t evaluations = 0;  // budgets evaluated in all
  std::vector<std::vector<double>> parameter_values;  // per parameter, per sample (SI)
  std::vector<StudyMetric> metrics;
  std::size_t all_met = 0;  // samples meeting every requirement
  Interval p_all_met;
  std::string corner_method;  // how the worst corners were found
  std::vector<std::string> notes;
};

// The budget at the given parameter values (SI, in spec order); may be
// called from several threads at once. @throws InputError for a variant
// that does not load.
using VariantLoader = std::function<Budget(const std::vector<double>& values)>;

// The parameter values (SI) of design point u (uniforms, one per parameter).
std::vector<double> SampleValues(const UncertaintySpec& spec, const Eigen::LLT<Eigen::MatrixXd>& copula,
                                 const std::vector<double>& u);

// n Latin-hypercube samples of the spec's parameters (SI, in spec order;
// sample k's from (seed, k) as SampleDesign's): the tolerances a robust
// optimisation evaluates every design at.
std::vector<std::vector<double>> LatinHypercubeValues(const UncertaintySpec& spec, std::size_t n, std::uint64_t seed);

// The evaluations a shard made: the metric values (StudyMetric order) of
// evaluations [begin, end) of the study's `total`.
struct UncertaintyPart {
  std::size_t total = 0, begin = 0, end = 0;
  std::vector<std::vector<double>> values;  // [e - begin][metric]
};

// How many budgets the study evaluates (before the worst corners of a
// study of more than kMaxCornerParameters parameters, found after).
std::size_t UncertaintyEvaluationCount(const UncertaintySpec& spec, const UncertaintyOptions& options);

// The metric values of evaluations [begin, end) of the study (begin < end
// <= UncertaintyEvaluationCount), in parallel on options.threads: a block of
// a distributed run's work queue. @throws InputError as RunUncertainty.
std::vector<std::vector<double>> EvaluateUncertaintyRange(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                                          const VariantLoader& variant, std::size_t begin,
                                                          std::size_t end);

// Evaluates the shard's share of the study. progress as RunUncertainty's,
// over the share. @throws InputError as RunUncertainty.
UncertaintyPart EvaluateUncertaintyPart(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                        const VariantLoader& variant, const StudyShard& shard,
                                        const std::function<void(std::size_t, std::size_t)>& progress = {});

// The study from every evaluation's metric values (`values[e]`, e < the
// evaluation count, as the parts hold them): the same result, bit for bit,
// as RunUncertainty's with the same spec and options. Evaluates the nominal
// budget again (for its metrics' names) and, for many parameters, the worst
// corners. @throws InputError for values of the wrong size, naming the
// evaluation.
UncertaintyResult SummariseUncertainty(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                       const VariantLoader& variant, const std::vector<std::vector<double>>& values);

// Runs the study. progress(done, total) as EvaluateSweep's.
// @throws InputError naming the sample and its values for a sample whose
//   budget fails to load or evaluate.
UncertaintyResult RunUncertainty(const UncertaintySpec& spec, const UncertaintyOptions& options,
                                 const VariantLoader& variant,
                                 const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace deb
