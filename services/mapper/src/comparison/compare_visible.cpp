#include "comparison/compare_visible.hpp"

#include <algorithm>

namespace relplane::mapper {

void CompareVisible(int64_t iteration, const std::vector<int64_t>& visible,
                    const MapperOptions& options, MapperState& state) {
  for (int64_t id : visible) {
    RltPlane* plane = state.Plane(id);
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
    RltPlane* plane = state.Plane(id);
    if (plane == nullptr) continue;
    const size_t ii =
        static_cast<size_t>(std::lower_bound(visible.begin(), visible.end(), id) - visible.begin());
    for (int64_t g : plane->groups) {
      Group& group = state.groups[g];
      for (int64_t other : group.members) {
        if (other == id) continue;
        const auto found = std::lower_bound(visible.begin(), visible.end(), other);
        if (found == visible.end() || *found != other) continue;
        // A frozen group keeps its relative map (§II.F); the comparison still learns (static
        // edges now, for localisation).
        if (!group.Frozen()) group.dirty = true;
        const PairKey key = KeyOf(id, other);
        const size_t jj = static_cast<size_t>(found - visible.begin());
        char& pair_done = done[std::min(ii, jj) * n + std::max(ii, jj)];
        if (pair_done) continue;
        pair_done = 1;
        auto it = state.comparisons.try_emplace(key, key.first, key.second).first;
        it->second.Update(*state.Plane(key.first), *state.Plane(key.second), iteration,
                          options.comparison, options.registration.last_seen_window);
      }
    }
  }
}

}  // namespace relplane::mapper
