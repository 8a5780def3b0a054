#include "plane_store/view_cuts.hpp"

#include <algorithm>
#include <iterator>
#include <set>

namespace relplane::mapper {

int MarkViewCuts(const LearnedFrustum& frustum, double static_std, PlaneStore& store,
                 Grouping& grouping) {
  const double max_spacing = MaxEndSpacing(static_std);
  int marked = 0;
  for (auto& entry : store.planes) {
    const int64_t id = entry.first;
    RltPlane& plane = entry.second;  // named, not a structured binding: the lambda below uses it
    const auto& all = plane.Observations();
    std::set<int64_t> changed;  // iterations with a newly cut edge
    for (size_t i = 0; i < all.size(); ++i) {
      for (int e = 0; e < 2; ++e) {
        const Observation& obs = all[i];
        if (obs.ViewCut(e)) continue;
        if (frustum.Clipped(obs.edge[e], obs.edge[1 - e])) {
          plane.MarkCut(i, e);
        } else if (!obs.cut[e] && frustum.EdgeSpacing(obs.edge[e], obs.d) > max_spacing) {
          plane.MarkCoarse(i, e);
        } else {
          continue;
        }
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
