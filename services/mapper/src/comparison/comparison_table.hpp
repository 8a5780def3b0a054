#pragma once
// Every pair of rltplanes compared so far (§II.C), owned by the comparison step.

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <unordered_map>
#include <utility>

#include "comparison/comparison.hpp"

namespace relplane::mapper {

using PairKey = std::pair<int64_t, int64_t>;
inline PairKey KeyOf(int64_t a, int64_t b) { return a < b ? PairKey{a, b} : PairKey{b, a}; }
struct PairKeyHash {
  size_t operator()(const PairKey& k) const {
    // Plane ids are small and dense: mix the two so neighbouring pairs spread over the buckets.
    const uint64_t h = static_cast<uint64_t>(k.first) * 0x9E3779B97F4A7C15ULL ^
                       static_cast<uint64_t>(k.second) * 0xC2B2AE3D27D4EB4FULL;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

struct ComparisonTable {
  // Hashed, not ordered: the relative and global maps look up every pair of a group's members
  // at every build, and a tree's look-ups were most of that time (nothing walks them in order).
  std::unordered_map<PairKey, Comparison, PairKeyHash> pairs;

  const Comparison* Find(int64_t a, int64_t b) const {
    auto it = pairs.find(KeyOf(a, b));
    return it == pairs.end() ? nullptr : &it->second;
  }
  // Drops every comparison of rltplane `id` (it left the map, §II.F).
  void Forget(int64_t id) {
    for (auto it = pairs.begin(); it != pairs.end();) {
      it = it->first.first == id || it->first.second == id ? pairs.erase(it) : std::next(it);
    }
  }
};

}  // namespace relplane::mapper
