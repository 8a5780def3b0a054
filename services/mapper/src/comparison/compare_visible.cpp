#include "comparison/compare_visible.hpp"

#include <algorithm>
#include <set>

namespace relplane::mapper {

std::set<int64_t> CompareVisible(int64_t iteration, const std::vector<int64_t>& visible,
                                 const MapperOptions& options, const Grouping& grouping,
                                 PlaneStore& store, ComparisonTable& comparisons) {
  std::set<int64_t> rebuild;
  for (int64_t id : visible) {
    RltPlane* plane = store.Plane(id);
    if (plane == nullptr) continue;
    plane->static_now[0] = plane->static_now[1] = false;
    plane->static_now_iteration = iteration;
  }
  // Pairs already updated, by their planes' indices in `visible` (sorted): a flag matrix, not a
  // set of keys, whose nodes cost more than the look-ups they saved.
  const size_t n = visible.size();
  std::vector<char> done(n * n, 0);
  for (size_t i = 0; i < n; ++i) {
    const int64_t id = visible[i];
    RltPlane* plane = store.Plane(id);
    if (plane == nullptr) continue;
    const size_t ii =
        static_cast<size_t>(std::lower_bound(visible.begin(), visible.end(), id) - visible.begin());
    for (int64_t g : plane->groups) {
      const Group& group = grouping.groups[g];
      for (int64_t other : group.members) {
        if (other == id) continue;
        const auto found = std::lower_bound(visible.begin(), visible.end(), other);
        if (found == visible.end() || *found != other) continue;
        // A frozen group keeps its relative map (§II.F); the comparison still learns (static
        // edges now, for localisation).
        if (!group.Frozen()) rebuild.insert(g);
        const PairKey key = KeyOf(id, other);
        const size_t jj = static_cast<size_t>(found - visible.begin());
        char& pair_done = done[std::min(ii, jj) * n + std::max(ii, jj)];
        if (pair_done) continue;
        pair_done = 1;
        auto it = comparisons.pairs.try_emplace(key, key.first, key.second).first;
        it->second.Update(*store.Plane(key.first), *store.Plane(key.second), iteration,
                          options.comparison, options.registration.last_seen_window);
      }
    }
  }
  return rebuild;
}

}  // namespace relplane::mapper
