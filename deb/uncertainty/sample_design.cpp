#include "deb/uncertainty/sample_design.h"

#include <Random123/philox.h>

#include <boost/random/sobol.hpp>
#include <cmath>
#include <numeric>

#include "deb/core/error.h"

namespace deb {

namespace {

// The streams a design draws from, one per purpose.
enum Stream : std::uint64_t { kPoints = 1, kStrata = 2, kShift = 3 };

// 53 random bits as a double in (0, 1): (n + 0.5) / 2^53.
double Unit(std::uint64_t bits) { return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53; }

}  // namespace

double KeyedUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index, std::uint64_t k) {
  // Philox-2x64-10: key (seed), counter (index, stream and k / 2): two
  // 64-bit words per call.
  const r123::Philox2x64::key_type key = {{seed}};
  const r123::Philox2x64::ctr_type counter = {{index, (stream << 56) ^ (k >> 1)}};
  const r123::Philox2x64::ctr_type out = r123::Philox2x64()(counter, key);
  return Unit(out.v[k & 1]);
}

struct SampleDesign::Sobol {
  explicit Sobol(std::size_t dimensions) : engine(dimensions) {}
  boost::random::sobol engine;
};

std::size_t MaxSobolDimensions() { return boost::random::default_sobol_table::max_dimension; }

SampleDesign::SampleDesign(SamplingMethod method, std::uint64_t seed, std::size_t samples, std::size_t dimensions)
    : method_(method), seed_(seed), samples_(samples), dimensions_(dimensions) {
  DEB_DEMAND(samples >= 1 && dimensions >= 1);
  if (method == SamplingMethod::kLatinHypercube) {
    // A Fisher-Yates shuffle of the strata per dimension, from the keyed stream.
    strata_.resize(dimensions);
    for (std::size_t d = 0; d < dimensions; ++d) {
      std::vector<std::uint32_t>& s = strata_[d];
      s.resize(samples);
      std::iota(s.begin(), s.end(), 0u);
      for (std::size_t i = samples - 1; i > 0; --i) {
        const double u = KeyedUniform(seed, kStrata, d, i);
        const auto j = static_cast<std::size_t>(u * static_cast<double>(i + 1));
        std::swap(s[i], s[std::min(j, i)]);
      }
    }
  }
  if (method == SamplingMethod::kSobol) {
    DEB_DEMAND(dimensions <= MaxSobolDimensions());
    sobol_ = std::make_unique<Sobol>(dimensions);
    for (std::size_t d = 0; d < dimensions; ++d) shift_.push_back(KeyedUniform(seed, kShift, 0, d));
  }
}

SampleDesign::~SampleDesign() = default;
SampleDesign::SampleDesign(SampleDesign&&) noexcept = default;

std::vector<double> SampleDesign::Point(std::size_t index) const {
  DEB_DEMAND(index < samples_);
  std::vector<double> u(dimensions_);
  switch (method_) {
    case SamplingMethod::kMonteCarlo:
      for (std::size_t d = 0; d < dimensions_; ++d) u[d] = KeyedUniform(seed_, kPoints, index, d);
      break;
    case SamplingMethod::kLatinHypercube:
      for (std::size_t d = 0; d < dimensions_; ++d)
        u[d] = (strata_[d][index] + KeyedUniform(seed_, kPoints, index, d)) / static_cast<double>(samples_);
      break;
    case SamplingMethod::kSobol: {
      // Boost's engine starts after the origin (its seed(0) is the point
      // (1/2, ...)): the origin is point 0 here, the engine's k point k + 1.
      boost::random::sobol engine = sobol_->engine;  // a copy: Point is called from several threads
      if (index > 0) engine.seed(static_cast<boost::random::sobol::result_type>(index - 1));
      for (std::size_t d = 0; d < dimensions_; ++d) {
        // The engine's 64-bit integer as a fraction, rotated by the seed's shift.
        const double x = index == 0 ? 0.0 : std::ldexp(static_cast<double>(engine() >> 11), -53);
        double v = x + shift_[d];
        v -= std::floor(v);
        // Keep strictly inside (0, 1) for the quantile functions.
        u[d] = std::min(std::max(v, 0x1.0p-54), 1.0 - 0x1.0p-53);
      }
      break;
    }
  }
  return u;
}

}  // namespace deb
