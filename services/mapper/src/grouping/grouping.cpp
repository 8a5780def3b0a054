#include "grouping/grouping.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace relplane::mapper {
namespace {

bool Covisible(const PlaneStore& store, const RltPlane& r, int64_t other, int64_t now,
               const GroupingOptions& options) {
  const RltPlane* m = store.Plane(other);
  return m != nullptr && CommonRecent(r, *m, now, options.covisible_window) >= options.min_common;
}

// §II.B "checks if an ungrouped rltplane is present in the same time interval as every other
// rltplane in a given grouping".
bool FitsGroup(const PlaneStore& store, const RltPlane& r, const Group& g, int64_t now,
               const GroupingOptions& options) {
  // A frozen group's relative map is no longer rebuilt (§II.F): it takes no new member.
  if (g.Frozen()) return false;
  if (std::find(g.members.begin(), g.members.end(), r.Id()) != g.members.end()) return false;
  for (int64_t m : g.members) {
    if (!Covisible(store, r, m, now, options)) return false;
  }
  return true;
}

// §II.C compares planes by their orientation relative to each other, which is the same from
// every pose for two walls. A plane whose relative orientation wanders is not being measured as
// one wall: a sliver of a wall beside a door jamb, fitted with some of the jamb's points, turned
// 12 degrees over its first 8 sightings as it grew, was grouped and mapped beside the wall it
// belongs to (a duplicate 3 degrees off), and localising against it turned the pose 8 degrees.
// Judged against the plane seen with it most often over its latest sightings; a plane seen alone
// cannot be judged and counts as steady.
bool Steady(const PlaneStore& store, const RltPlane& r, const GroupingOptions& options) {
  const auto& all = r.Observations();
  const size_t n = std::min(all.size(), static_cast<size_t>(std::max(options.min_observations, 1)));
  const size_t from = all.size() - n;
  int best_common = 0;
  double best_spread = 0.0;
  for (int64_t id : store.recent) {
    if (id == r.Id()) continue;
    const auto it = store.planes.find(id);
    if (it == store.planes.end()) continue;
    double s = 0.0, c = 0.0;
    std::vector<double> deltas;
    for (size_t i = from; i < all.size(); ++i) {
      const Observation* other = it->second.At(all[i].iteration);
      if (other == nullptr) continue;
      const double d = all[i].Alpha() - other->Alpha();
      deltas.push_back(d);
      s += std::sin(d), c += std::cos(d);
    }
    const int common = static_cast<int>(deltas.size());
    if (common < options.min_common_orientation || common <= best_common) continue;
    const double mean = std::atan2(s, c);
    double sq = 0.0;
    for (double d : deltas) {
      const double e = std::remainder(d - mean, 2.0 * M_PI);
      sq += e * e;
    }
    best_common = common;
    best_spread = std::sqrt(sq / common);
  }
  return best_spread <= options.max_orientation_spread;
}

void Join(PlaneStore& store, Group& g, int64_t id) {
  g.members.push_back(id);
  g.dirty = true;
  store.Plane(id)->groups.push_back(g.id);
}

// Places one rltplane that is ready to be grouped.
void Place(Grouping& grouping, PlaneStore& store, int64_t id, int64_t now,
           const GroupingOptions& options) {
  const RltPlane& r = *store.Plane(id);
  const int n = static_cast<int>(grouping.groups.size());
  const int first = std::max(0, n - options.recent_groups);
  for (int g = n - 1; g >= first; --g) {
    if (FitsGroup(store, r, grouping.groups[g], now, options)) {
      Join(store, grouping.groups[g], id);
      return;
    }
  }
  // §II.B "a new one is created [...] with rltplanes from the previous grouping that are in the
  // same time interval as the ungrouped rltplane".
  Group group;
  group.id = n;
  group.created = now;
  grouping.groups.push_back(group);
  Group& fresh = grouping.groups.back();
  Join(store, fresh, id);
  for (int g = n - 1; g >= first; --g) {
    for (int64_t m : grouping.groups[g].members) {
      if (std::find(fresh.members.begin(), fresh.members.end(), m) != fresh.members.end()) {
        continue;
      }
      if (Covisible(store, *store.Plane(id), m, now, options)) Join(store, fresh, m);
    }
  }
}

bool ShareAGroup(const RltPlane& a, const RltPlane& b) {
  // Both lists are in creation order.
  auto i = a.groups.begin(), j = b.groups.begin();
  while (i != a.groups.end() && j != b.groups.end()) {
    if (*i < *j) {
      ++i;
    } else if (*j < *i) {
      ++j;
    } else {
      return true;
    }
  }
  return false;
}

// Does `r` already share a group with every grouped plane of this view it is co-visible with?
// Then every pair in view is compared in a group that already exists (§II.C), and its
// relative map covers the view: a route driven again and again adds no group once each pair
// seen together has been grouped together.
bool CoveredByGroups(const PlaneStore& store, const RltPlane& r,
                     const std::vector<int64_t>& visible, int64_t now,
                     const GroupingOptions& options) {
  for (int64_t other : visible) {
    const RltPlane* o = store.Plane(other);
    if (o == nullptr || o->groups.empty() || other == r.Id()) continue;
    if (!ShareAGroup(r, *o) && Covisible(store, r, other, now, options)) return false;
  }
  return true;
}

}  // namespace

int CommonRecent(const RltPlane& a, const RltPlane& b, int64_t now, int window) {
  return CommonSince(a, b, now - window + 1);
}

int CommonSince(const RltPlane& a, const RltPlane& b, int64_t from) {
  const auto& oa = a.Observations();
  const auto& ob = b.Observations();
  size_t i = a.LowerBound(from), j = b.LowerBound(from);
  int common = 0;
  while (i < oa.size() && j < ob.size()) {
    if (oa[i].iteration < ob[j].iteration) {
      ++i;
    } else if (ob[j].iteration < oa[i].iteration) {
      ++j;
    } else {
      ++common, ++i, ++j;
    }
  }
  return common;
}

void UpdateGroups(const std::vector<int64_t>& created, const std::vector<int64_t>& visible,
                  int64_t now, const GroupingOptions& options, Grouping& grouping,
                  PlaneStore& store) {
  grouping.ungrouped.insert(grouping.ungrouped.end(), created.begin(), created.end());
  // The ungrouped list: ready rltplanes are placed, stale ones dropped.
  std::vector<int64_t> waiting;
  for (int64_t id : grouping.ungrouped) {
    RltPlane* r = store.Plane(id);
    if (r == nullptr) continue;
    if (r->Count() >= options.min_observations && Steady(store, *r, options)) {
      Place(grouping, store, id, now, options);
      continue;
    }
    if (now - r->FirstSeen() > options.ungrouped_timeout) {
      store.recent.erase(id);
      store.planes.erase(id);
      continue;
    }
    waiting.push_back(id);
  }
  grouping.ungrouped = std::move(waiting);
  // Re-seen rltplanes (backtracking, loop closure: §II.A end) rejoin the current groups so the
  // new relative maps link to them, unless they already share a group with every plane in
  // view they are co-visible with: then the old groups cover the view, and a later lap adds no
  // group there (the number of groups stays bounded on a route driven again and again).
  const int n = static_cast<int>(grouping.groups.size());
  for (int64_t id : visible) {
    RltPlane* r = store.Plane(id);
    if (r == nullptr || r->groups.empty()) continue;
    if (r->groups.back() >= n - options.recent_groups) continue;
    if (CommonRecent(*r, *r, now, options.covisible_window) < options.min_common) continue;
    if (CoveredByGroups(store, *r, visible, now, options)) continue;
    Place(grouping, store, id, now, options);
  }
}

}  // namespace relplane::mapper
