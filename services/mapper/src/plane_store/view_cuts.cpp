#include "plane_store/view_cuts.hpp"

#include <algorithm>
#include <iterator>
#include <set>

namespace relplane::mapper {

int MarkViewCuts(const LearnedFrustum& frustum, PlaneStore& store, Grouping& grouping) {
  int marked = 0;
  for (auto& entry : store.planes) {
    const int64_t id = entry.first;
    RltPlane& plane = entry.second;  // named, not a structured binding: the lambda below uses it
    const auto& all = plane.Observations();
    std::set<int64_t> changed;  // iterations with a newly cut edge
    for (size_t i = 0; i < all.size(); ++i) {
      for (int e = 0; e < 2; ++e) {
        if (all[i].cut[e] || !frustum.Clipped(all[i].edge[e], all[i].edge[1 - e])) continue;
        plane.MarkCut(i, e);
        changed.insert(all[i].iteration);
        ++marked;
      }
    }
    if (changed.empty()) continue;
    // A sighting kept from one of those observations carries its cut flags.
    auto revise = [&](SeenWall& seen) {
      const Observation* obs = seen.valid ? plane.At(seen.iteration) : nullptr;
      if (obs == nullptr || changed.count(seen.iteration) == 0) return;
      for (int e = 0; e < 2; ++e) seen.cut[e] = seen.cut[e] || obs->cut[e];
    };
    revise(plane.first_seen);
    for (Group& group : grouping.groups) {
      if (std::find(group.members.begin(), group.members.end(), id) == group.members.end()) {
        continue;
      }
      if (auto it = group.seen.find(id); it != group.seen.end()) revise(it->second);
      if (auto it = group.seen_fixed.find(id); it != group.seen_fixed.end()) revise(it->second);
      for (auto it = group.shows_end.begin(); it != group.shows_end.end();) {
        it = std::get<0>(it->first) == id ? group.shows_end.erase(it) : std::next(it);
      }
      group.dirty = true;
    }
  }
  return marked;
}

}  // namespace relplane::mapper
