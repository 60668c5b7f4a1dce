// Where the samples of an uncertainty study fall in the unit cube: one
// point of uniform numbers in (0, 1) per sample, which the parameters'
// distributions (distribution.h) and their copula (uncertainty_study.h)
// turn into values.
//  - mc: independent uniforms from Random123's counter-based Philox
//    generator keyed by the seed, its counter the sample index and the
//    dimension: a sample's numbers depend on (seed, index) alone, never on
//    the threads, shards or order that evaluate it.
//  - lhs: Latin hypercube: in each dimension the N samples fall one into each
//    of N equal strata, the strata permuted per dimension by a shuffle drawn
//    from the same keyed stream, the place within a stratum from the
//    sample's own stream.
//  - sobol: Boost.Random's Sobol sequence (Joe-Kuo direction numbers),
//    points 0, 1, ..., each dimension shifted by a random offset modulo 1
//    drawn from the seed (Cranley-Patterson rotation): the origin becomes an
//    ordinary point, different seeds give different, equally even designs,
//    and the first 2^m points keep one point in each of 2^m (shifted) strata
//    of every dimension.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "deb/core/enum_names.h"

namespace deb {

enum class SamplingMethod { kMonteCarlo, kLatinHypercube, kSobol };
inline constexpr EnumName<SamplingMethod> kSamplingMethodNames[] = {
    {SamplingMethod::kMonteCarlo, "mc"}, {SamplingMethod::kLatinHypercube, "lhs"}, {SamplingMethod::kSobol, "sobol"}};
constexpr EnumNames<SamplingMethod> NamesOf(SamplingMethod) { return kSamplingMethodNames; }
// @throws InputError listing the allowed values.
inline SamplingMethod ParseSamplingMethod(const std::string& text) {
  return ParseEnum<SamplingMethod>(text, "sampling method");
}

// The largest dimension of a Sobol design (Boost's table of direction numbers).
std::size_t MaxSobolDimensions();

class SampleDesign {
 public:
  // `samples` points of `dimensions` numbers each. DEB_DEMANDs samples >= 1,
  // dimensions >= 1, and for sobol dimensions <= MaxSobolDimensions().
  SampleDesign(SamplingMethod method, std::uint64_t seed, std::size_t samples, std::size_t dimensions);
  ~SampleDesign();
  SampleDesign(SampleDesign&&) noexcept;

  // Point `index` (< samples): `dimensions` numbers in (0, 1). Safe to call
  // from several threads at once.
  std::vector<double> Point(std::size_t index) const;

  std::size_t samples() const { return samples_; }
  std::size_t dimensions() const { return dimensions_; }

 private:
  SamplingMethod method_;
  std::uint64_t seed_;
  std::size_t samples_, dimensions_;
  std::vector<std::vector<std::uint32_t>> strata_;  // lhs: per dimension, the stratum of each sample
  std::vector<double> shift_;                        // sobol: per dimension
  struct Sobol;
  std::unique_ptr<Sobol> sobol_;
};

// Uniform number `k` in (0, 1) of the stream keyed by (seed, stream, index):
// the Philox draw every design is made of. Never 0 or 1.
double KeyedUniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index, std::uint64_t k);

}  // namespace deb
