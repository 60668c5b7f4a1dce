// The statistics of an uncertainty study's samples: percentiles, the
// probability of meeting a requirement with its Wilson interval, Spearman's
// rank correlation, and the Sobol indices of the variance by the
// Saltelli / Jansen estimators.
#pragma once

#include <cstddef>
#include <vector>

namespace deb {

// The p-quantile (0 <= p <= 1) of `values`, linear between order statistics
// (Hyndman-Fan type 7, as numpy's default). DEB_DEMANDs values not empty.
double Percentile(std::vector<double> values, double p);

struct Moments {
  double mean = 0.0;
  double sd = 0.0;  // with N - 1
};
Moments MeanAndSd(const std::vector<double>& values);

// The Wilson score interval of a proportion: `successes` of `trials`, at the
// normal quantile z (1.959964 for 95 %). DEB_DEMANDs trials >= 1.
struct Interval {
  double low = 0.0, high = 0.0;
};
Interval WilsonInterval(std::size_t successes, std::size_t trials, double z = 1.959963984540054);

// Spearman's rank correlation of x and y (ties get their average rank);
// 0 when either is constant. DEB_DEMANDs equal sizes >= 2.
double SpearmanCorrelation(const std::vector<double>& x, const std::vector<double>& y);

// The bound a rank correlation of n independent samples stays within with
// probability about 95 % (z = 1.96): z / sqrt(n - 1), Spearman's rho being
// near normal with variance 1 / (n - 1) under independence. A correlation
// within it says nothing of the sign of a parameter's effect. DEB_DEMANDs n >= 2.
double RankCorrelationNoise(std::size_t n, double z = 1.959963984540054);

// First-order and total Sobol indices of parameter i from the model's values
// on the two independent designs A and B and on A with column i from B
// (a_b): S_i = mean(f_B (f_AB - f_A)) / V (Saltelli 2010),
// ST_i = mean((f_A - f_AB)^2) / (2 V) (Jansen 1999), V the variance of
// f_A and f_B together. Both 0 when V is 0.
struct SobolIndices {
  double first = 0.0, total = 0.0;
};
SobolIndices SobolIndicesOf(const std::vector<double>& f_a, const std::vector<double>& f_b,
                            const std::vector<double>& f_ab);

}  // namespace deb
