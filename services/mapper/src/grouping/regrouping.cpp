#include "grouping/regrouping.hpp"

#include <algorithm>
#include <cstdint>

#include "global_map/relative_map.hpp"
#include "grouping/grouping.hpp"

namespace relplane::mapper {
namespace {

// The longest comparison interval `id` has with another member of `group`.
double MemberInterval(const ComparisonTable& comparisons, const Group& group, int64_t id) {
  double longest = 0.0;
  for (int64_t other : group.members) {
    if (other == id) continue;
    const Comparison* c = comparisons.Find(id, other);
    if (c != nullptr) longest = std::max(longest, c->Common());
  }
  return longest;
}

// Brings the comparisons of `id` with every member of `group` up to `now` from the stored
// observations: "these untransformed observations are used to recalculate a new grouping".
void CompareWithMembers(PlaneStore& store, ComparisonTable& comparisons, const Group& group,
                        int64_t id, int64_t now, const MapperOptions& options) {
  for (int64_t other : group.members) {
    if (other == id) continue;
    const PairKey key = KeyOf(id, other);
    auto it = comparisons.pairs.try_emplace(key, key.first, key.second).first;
    it->second.Update(*store.Plane(key.first), *store.Plane(key.second), now, options.comparison,
                      options.registration.last_seen_window);
  }
}

void Leave(PlaneStore& store, Group& group, int64_t id) {
  group.members.erase(std::remove(group.members.begin(), group.members.end(), id),
                      group.members.end());
  group.relative.members.erase(id);
  group.seen.erase(id);
  group.seen_fixed.erase(id);
  group.seen_line.erase(id);
  for (auto it = group.shows_end.begin(); it != group.shows_end.end();) {
    it = std::get<0>(it->first) == id ? group.shows_end.erase(it) : std::next(it);
  }
  group.finest_end.erase({id, 0});
  group.finest_end.erase({id, 1});
  group.dirty = true;
  RltPlane* plane = store.Plane(id);
  plane->groups.erase(std::remove(plane->groups.begin(), plane->groups.end(), group.id),
                      plane->groups.end());
}

// "attempted to be placed into another group": the open group it shares the longest stored
// interval with, if that is long enough.
bool JoinAnother(Grouping& grouping, PlaneStore& store, ComparisonTable& comparisons,
                 const WorldMap& world, size_t left, int64_t id, int64_t now,
                 const MapperOptions& options) {
  const RltPlane& plane = *store.Plane(id);
  int best = options.regrouping.min_interval - 1;
  size_t target = grouping.groups.size();
  for (size_t h = grouping.open_from; h < grouping.groups.size(); ++h) {
    const Group& candidate = grouping.groups[h];
    if (h == left || candidate.Frozen()) continue;
    for (int64_t m : candidate.members) {
      const int common = CommonSince(plane, *store.Plane(m), INT64_MIN);
      if (common > best) best = common, target = h;
    }
  }
  if (target == grouping.groups.size()) return false;
  Group& group = grouping.groups[target];
  group.members.push_back(id);
  group.dirty = true;
  RltPlane& joined = *store.Plane(id);
  joined.groups.insert(std::upper_bound(joined.groups.begin(), joined.groups.end(), group.id),
                       group.id);
  CompareWithMembers(store, comparisons, group, id, now, options);
  if (group.stage != GroupStage::kNew)
    group.order = ChooseOrder(group, {store, comparisons, world}, options.comparison);
  return true;
}

// "it is removed from the map altogether".
void DropPlane(int64_t id, Grouping& grouping, PlaneStore& store, ComparisonTable& comparisons,
               WorldMap& world) {
  comparisons.Forget(id);
  world.Forget(id);
  grouping.Forget(id);
  store.Forget(id);
}

// The second evaluation of §II.F: members whose comparisons in the group are too short are
// taken out; one in no other group is placed into another group or dropped.
void RegroupMembers(Grouping& grouping, PlaneStore& store, ComparisonTable& comparisons,
                    WorldMap& world, size_t g, int64_t now, const MapperOptions& options) {
  Group& group = grouping.groups[g];
  if (group.members.size() < 2) return;
  // Pairs never compared since they were grouped (one left the view first) are compared now
  // over what both observed: the interval they really share.
  const std::vector<int64_t> members = group.members;
  for (size_t i = 0; i < members.size(); ++i) {
    for (size_t j = i + 1; j < members.size(); ++j) {
      if (comparisons.Find(members[i], members[j]) == nullptr &&
          CommonSince(*store.Plane(members[i]), *store.Plane(members[j]), INT64_MIN) > 0) {
        const PairKey key = KeyOf(members[i], members[j]);
        comparisons.pairs.try_emplace(key, key.first, key.second)
            .first->second.Update(*store.Plane(key.first), *store.Plane(key.second), now,
                                  options.comparison, options.registration.last_seen_window);
      }
    }
  }
  std::vector<int64_t> short_lived;
  for (int64_t m : members) {
    if (MemberInterval(comparisons, group, m) < options.regrouping.min_interval)
      short_lived.push_back(m);
  }
  for (int64_t id : short_lived) {
    Leave(store, group, id);
    if (!store.Plane(id)->groups.empty()) continue;  // another group still places it
    if (!JoinAnother(grouping, store, comparisons, world, g, id, now, options))
      DropPlane(id, grouping, store, comparisons, world);
  }
}

}  // namespace

int64_t ObservationHorizon(const MapperOptions& options) {
  return options.regrouping.freeze_after + options.grouping.covisible_window;
}

void Regroup(int64_t now, const MapperOptions& options, Grouping& grouping, PlaneStore& store,
             ComparisonTable& comparisons, WorldMap& world) {
  const RegroupingOptions& o = options.regrouping;
  for (size_t g = grouping.open_from; g < grouping.groups.size(); ++g) {
    Group& group = grouping.groups[g];
    const int64_t age = now - group.created;
    if (o.enabled && group.stage == GroupStage::kNew && age >= o.reorder_after) {
      group.order = ChooseOrder(group, {store, comparisons, world}, options.comparison);
      group.stage = GroupStage::kReordered;
      group.dirty = true;
    }
    if (o.enabled && group.stage == GroupStage::kReordered && age >= o.regroup_after) {
      RegroupMembers(grouping, store, comparisons, world, g, now, options);
      group.order = ChooseOrder(group, {store, comparisons, world}, options.comparison);
      group.stage = GroupStage::kRegrouped;
      group.dirty = true;
    }
    // Past the horizon the relative map is frozen (built once more if dirty): the
    // observations it came from are about to be dropped, and a re-seen group costs nothing.
    if (group.stage != GroupStage::kFrozen && age >= o.freeze_after) {
      group.stage = GroupStage::kFrozen;
    }
  }
  while (grouping.open_from < grouping.groups.size() &&
         grouping.groups[grouping.open_from].Frozen()) {
    ++grouping.open_from;
  }
}

void DropOldObservations(const std::vector<int64_t>& visible, int64_t now,
                         const MapperOptions& options, PlaneStore& store) {
  const int64_t before = now - ObservationHorizon(options);
  for (int64_t id : visible) {
    if (RltPlane* plane = store.Plane(id)) plane->DropBefore(before);
  }
  // Planes out of view keep theirs until the next sweep.
  if (store.last_sweep >= 0 && now - store.last_sweep < options.regrouping.sweep_period) return;
  store.last_sweep = now;
  for (auto& [id, plane] : store.planes) plane.DropBefore(before);
}

}  // namespace relplane::mapper
