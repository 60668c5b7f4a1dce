#include "deb/uncertainty/distribution.h"

#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/triangular.hpp>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "deb/core/error.h"
#include "deb/core/number_text.h"

namespace deb {

namespace {

const boost::math::normal_distribution<double> kStandardNormal(0.0, 1.0);

double Pdf(double z) { return boost::math::pdf(kStandardNormal, z); }

// The normal (mean, sigma) truncated to [min, max]: its quantile at u,
// computed on the side of the mean where the truncation's probabilities are
// not rounded away (a window far in the upper tail is mirrored).
double TruncatedNormalQuantile(double mean, double sigma, double min, double max, double u) {
  const double a = (min - mean) / sigma, b = (max - mean) / sigma;
  if (a > 0.0) return -TruncatedNormalQuantile(-mean, sigma, -max, -min, 1.0 - u);
  const double pa = StandardNormalCdf(a), pb = StandardNormalCdf(b);
  const double z = StandardNormalQuantile(pa + u * (pb - pa));
  return std::min(max, std::max(min, mean + sigma * z));
}

}  // namespace

double StandardNormalQuantile(double u) { return boost::math::quantile(kStandardNormal, u); }
double StandardNormalCdf(double z) { return boost::math::cdf(kStandardNormal, z); }

double Distribution::Quantile(double u) const {
  DEB_DEMAND(u > 0.0 && u < 1.0);
  switch (kind) {
    case DistributionKind::kNormal:
      return mean + sigma * StandardNormalQuantile(u);
    case DistributionKind::kUniform:
      return min + u * (max - min);
    case DistributionKind::kLogNormal:
      return mean * std::exp(sigma * StandardNormalQuantile(u));
    case DistributionKind::kTruncatedNormal:
      return TruncatedNormalQuantile(mean, sigma, min, max, u);
    case DistributionKind::kTriangular:
      return boost::math::quantile(boost::math::triangular_distribution<double>(min, mode, max), u);
    case DistributionKind::kDiscrete: {
      double cumulative = 0.0;
      for (std::size_t i = 0; i + 1 < values.size(); ++i) {
        cumulative += probabilities[i];
        if (u < cumulative) return values[i];
      }
      return values.back();
    }
  }
  return 0.0;
}

double Distribution::Mean() const {
  switch (kind) {
    case DistributionKind::kNormal:
      return mean;
    case DistributionKind::kUniform:
      return 0.5 * (min + max);
    case DistributionKind::kLogNormal:
      return mean * std::exp(0.5 * sigma * sigma);
    case DistributionKind::kTruncatedNormal: {
      const double a = (min - mean) / sigma, b = (max - mean) / sigma;
      const double z = StandardNormalCdf(b) - StandardNormalCdf(a);
      return mean + sigma * (Pdf(a) - Pdf(b)) / z;
    }
    case DistributionKind::kTriangular:
      return (min + mode + max) / 3.0;
    case DistributionKind::kDiscrete:
      return std::inner_product(values.begin(), values.end(), probabilities.begin(), 0.0);
  }
  return 0.0;
}

double Distribution::StandardDeviation() const {
  switch (kind) {
    case DistributionKind::kNormal:
      return sigma;
    case DistributionKind::kUniform:
      return (max - min) / std::sqrt(12.0);
    case DistributionKind::kLogNormal: {
      const double s2 = sigma * sigma;
      return mean * std::sqrt(std::expm1(s2) * std::exp(s2));
    }
    case DistributionKind::kTruncatedNormal: {
      const double a = (min - mean) / sigma, b = (max - mean) / sigma;
      const double z = StandardNormalCdf(b) - StandardNormalCdf(a);
      const double d = (Pdf(a) - Pdf(b)) / z;
      return sigma * std::sqrt(std::max(0.0, 1.0 + (a * Pdf(a) - b * Pdf(b)) / z - d * d));
    }
    case DistributionKind::kTriangular:
      return std::sqrt((min * min + mode * mode + max * max - min * mode - min * max - mode * max) / 18.0);
    case DistributionKind::kDiscrete: {
      const double m = Mean();
      double v = 0.0;
      for (std::size_t i = 0; i < values.size(); ++i) v += probabilities[i] * (values[i] - m) * (values[i] - m);
      return std::sqrt(v);
    }
  }
  return 0.0;
}

bool Distribution::Bounded() const {
  return kind == DistributionKind::kUniform || kind == DistributionKind::kTruncatedNormal ||
         kind == DistributionKind::kTriangular || kind == DistributionKind::kDiscrete;
}

namespace {
constexpr double kBoxTail = 0.0013498980316301;  // Phi(-3)
}

double Distribution::BoxLow() const {
  if (kind == DistributionKind::kDiscrete) return *std::min_element(values.begin(), values.end());
  return Bounded() ? min : Quantile(kBoxTail);
}

double Distribution::BoxHigh() const {
  if (kind == DistributionKind::kDiscrete) return *std::max_element(values.begin(), values.end());
  return Bounded() ? max : Quantile(1.0 - kBoxTail);
}

std::string Distribution::Problem() const {
  const auto finite = [](double v) { return std::isfinite(v); };
  switch (kind) {
    case DistributionKind::kNormal:
    case DistributionKind::kTruncatedNormal:
    case DistributionKind::kLogNormal:
      if (!finite(mean)) return "the value " + NumberText(mean) + " is not finite";
      if (!finite(sigma) || sigma <= 0.0) return "sigma " + NumberText(sigma) + " must be finite and > 0";
      if (kind == DistributionKind::kLogNormal && mean <= 0.0)
        return "a log-normal parameter's value (its median) " + NumberText(mean) + " must be > 0";
      if (kind != DistributionKind::kTruncatedNormal) return "";
      [[fallthrough]];
    case DistributionKind::kUniform:
    case DistributionKind::kTriangular:
      if (!finite(min) || !finite(max)) return "min and max must be finite";
      if (!(min < max)) return "min " + NumberText(min) + " must be below max " + NumberText(max);
      if (kind == DistributionKind::kTriangular && !(mode >= min && mode <= max))
        return "the mode (the parameter's value) " + NumberText(mode) + " must lie within [" + NumberText(min) + ", " +
               NumberText(max) + "]";
      if (kind == DistributionKind::kTruncatedNormal &&
          StandardNormalCdf((max - mean) / sigma) - StandardNormalCdf((min - mean) / sigma) < 1e-12)
        return "[min, max] = [" + NumberText(min) + ", " + NumberText(max) +
               "] holds almost none of the normal's probability (it lies beyond 7 sigma of the value)";
      return "";
    case DistributionKind::kDiscrete: {
      if (values.empty()) return "no values";
      if (values.size() != probabilities.size())
        return std::to_string(probabilities.size()) + " probabilities for " + std::to_string(values.size()) + " values";
      double sum = 0.0;
      for (std::size_t i = 0; i < values.size(); ++i) {
        if (!finite(values[i])) return "value " + NumberText(values[i]) + " is not finite";
        if (!finite(probabilities[i]) || probabilities[i] < 0.0)
          return "probability " + NumberText(probabilities[i]) + " must be finite and >= 0";
        sum += probabilities[i];
      }
      if (std::abs(sum - 1.0) > 1e-9) return "the probabilities add up to " + NumberText(sum) + ", not 1";
      return "";
    }
  }
  return "";
}

std::string Distribution::Text() const { return Texts(NumberText, NumberText); }

std::string Distribution::Text(double unit_si) const {
  return Texts([unit_si](double v) { return SignificantText(v / unit_si, 4); },
               [](double v) { return SignificantText(v, 4); });
}

std::string Distribution::Texts(const std::function<std::string(double)>& value,
                                const std::function<std::string(double)>& pure) const {
  switch (kind) {
    case DistributionKind::kNormal:
      return "normal(mean " + value(mean) + ", sigma " + value(sigma) + ")";
    case DistributionKind::kUniform:
      return "uniform(" + value(min) + ", " + value(max) + ")";
    case DistributionKind::kLogNormal:
      return "lognormal(median " + value(mean) + ", sigma of log " + pure(sigma) + ")";
    case DistributionKind::kTruncatedNormal:
      return "truncated normal(mean " + value(mean) + ", sigma " + value(sigma) + ", within [" +
             value(min) + ", " + value(max) + "])";
    case DistributionKind::kTriangular:
      return "triangular(" + value(min) + ", mode " + value(mode) + ", " + value(max) + ")";
    case DistributionKind::kDiscrete: {
      std::string s = "discrete(";
      for (std::size_t i = 0; i < values.size(); ++i)
        s += (i ? ", " : "") + value(values[i]) + " p " + pure(probabilities[i]);
      return s + ")";
    }
  }
  return "";
}

}  // namespace deb
