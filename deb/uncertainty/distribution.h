// The distribution of an uncertain parameter (a budget parameter with a
// `distribution:`), over the parameter's value in coherent SI units, given
// by its inverse CDF: a sample is Quantile(u) of a uniform u in (0, 1), so
// that Monte Carlo, Latin hypercube and Sobol designs and the Gaussian
// copula of correlated parameters (uncertainty_design.h) all sample through
// one function. Quantiles come from Boost.Math.
#pragma once

#include <functional>
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
  // The same for a reader: values divided by `unit_si` (SI per display
  // unit, as UncertainParameter::unit_si) and set to 4 significant digits
  // ("uniform(0.07, 0.13)" for N s/m shown in N s/mm); a lognormal's sigma
  // of log and a discrete one's probabilities are dimensionless, not scaled.
  std::string Text(double unit_si) const;

 private:
  // Text with `value` formatting the values, `pure` the dimensionless numbers.
  std::string Texts(const std::function<std::string(double)>& value,
                    const std::function<std::string(double)>& pure) const;
};

// The quantile of the standard normal distribution at u in (0, 1), and its CDF.
double StandardNormalQuantile(double u);
double StandardNormalCdf(double z);

}  // namespace deb
