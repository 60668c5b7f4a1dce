// The distribution of an uncertain parameter (a budget parameter with a
// `distribution:`), over the parameter's value in coherent SI units, given
// by its inverse CDF: a sample is Quantile(u) of a uniform u in (0, 1), so
// that Monte Carlo, Latin hypercube and Sobol designs and the Gaussian
// copula of correlated parameters (uncertainty_design.h) all sample through
// one function. Quantiles come from Boost.Math.
#pragma once

#include <string>
#include <vector>

namespace deb {

enum class DistributionKind { kNormal, kUniform, kLogNormal, kTruncatedNormal, kTriangular, kDiscrete };

struct Distribution {
  DistributionKind kind = DistributionKind::kNormal;
  // kNormal, kTruncatedNormal: mean and sigma (of the untruncated normal).
  // kLogNormal: median and sigma of log(x).
  double mean = 0.0, sigma = 0.0;
  // kUniform, kTruncatedNormal, kTriangular: the bounds; kTriangular: `mode` too.
  double min = 0.0, max = 0.0, mode = 0.0;
  // kDiscrete: the values and their probabilities (summing to 1).
  std::vector<double> values, probabilities;

  // The value below which a fraction u of the distribution lies; u in (0, 1).
  double Quantile(double u) const;
  // The mean of the distribution (for the first-order estimate).
  double Mean() const;
  // The standard deviation of the distribution.
  double StandardDeviation() const;
  // The tolerance box's ends: the bounds of a bounded distribution, else
  // the quantiles 0.135 % and 99.865 % (the mean +- 3 sigma of a normal).
  double BoxLow() const;
  double BoxHigh() const;
  bool Bounded() const;

  // What is wrong with it ("sigma -1 must be > 0"), or "".
  std::string Problem() const;
  // "normal(mean 5.2e+04, sigma 2600)", values in SI.
  std::string Text() const;
};

// The quantile of the standard normal distribution at u in (0, 1), and its CDF.
double StandardNormalQuantile(double u);
double StandardNormalCdf(double z);

}  // namespace deb
