// A share of a study's evaluations, for a study split over processes or
// machines (deb uncertainty|sweep --shard K/N, deb merge): shard `index` of
// `count` (1-based) holds a contiguous block of the evaluation indices, the
// blocks' sizes differing by at most one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>

#include "deb/core/error.h"

namespace deb {

inline constexpr std::size_t kMaxShards = 100000;

struct StudyShard {
  std::size_t index = 1, count = 1;
  // 1 <= index <= count <= kMaxShards.
  bool Valid() const { return count >= 1 && count <= kMaxShards && index >= 1 && index <= count; }
  // [begin, end) of `total` evaluations. DEB_DEMANDs 1 <= index <= count.
  std::pair<std::size_t, std::size_t> Range(std::size_t total) const {
    DEB_DEMAND(count >= 1 && index >= 1 && index <= count);
    const auto edge = [&](std::size_t k) {
      return static_cast<std::size_t>(static_cast<std::uint64_t>(total) * k / count);
    };
    return {edge(index - 1), edge(index)};
  }
};

}  // namespace deb
