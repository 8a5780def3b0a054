#include "grouping/regrouping.hpp"

#include <algorithm>
#include <cstdint>

#include "grouping/grouping.hpp"
#include "global_map/relative_map.hpp"

namespace relplane::mapper {
namespace {

// The longest comparison interval `id` has with another member of `group`.
double MemberInterval(const MapperState& state, const Group& group, int64_t id) {
  double longest = 0.0;
  for (int64_t other : group.members) {
    if (other == id) continue;
    const Comparison* c = state.FindComparison(id, other);
    if (c != nullptr) longest = std::max(longest, c->Common());
  }
  return longest;
}

// Brings the comparisons of `id` with every member of `group` up to `now` from the stored
// observations: "these untransformed observations are used to recalculate a new grouping".
void CompareWithMembers(MapperState& state, const Group& group, int64_t id, int64_t now,
                        const MapperOptions& options) {
  for (int64_t other : group.members) {
    if (other == id) continue;
    const PairKey key = KeyOf(id, other);
    auto it = state.comparisons.try_emplace(key, key.first, key.second).first;
    it->second.Update(*state.Plane(key.first), *state.Plane(key.second), now,
                      options.comparison, options.registration.last_seen_window);
  }
}

void Leave(MapperState& state, Group& group, int64_t id) {
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
  RltPlane* plane = state.Plane(id);
  plane->groups.erase(std::remove(plane->groups.begin(), plane->groups.end(), group.id),
                      plane->groups.end());
}

// "attempted to be placed into another group": the open group it shares the longest stored
// interval with, if that is long enough.
bool JoinAnother(MapperState& state, size_t left, int64_t id, int64_t now,
                 const MapperOptions& options) {
  const RltPlane& plane = *state.Plane(id);
  int best = options.regrouping.min_interval - 1;
  size_t target = state.groups.size();
  for (size_t h = state.open_from; h < state.groups.size(); ++h) {
    const Group& candidate = state.groups[h];
    if (h == left || candidate.Frozen()) continue;
    for (int64_t m : candidate.members) {
      const int common = CommonSince(plane, *state.Plane(m), INT64_MIN);
      if (common > best) best = common, target = h;
    }
  }
  if (target == state.groups.size()) return false;
  Group& group = state.groups[target];
  group.members.push_back(id);
  group.dirty = true;
  RltPlane& joined = *state.Plane(id);
  joined.groups.insert(std::upper_bound(joined.groups.begin(), joined.groups.end(), group.id),
                       group.id);
  CompareWithMembers(state, group, id, now, options);
  if (group.stage != GroupStage::kNew) group.order = ChooseOrder(group, state, options.comparison);
  return true;
}

// "it is removed from the map altogether".
void DropPlane(MapperState& state, int64_t id) {
  for (auto it = state.comparisons.begin(); it != state.comparisons.end();) {
    it = it->first.first == id || it->first.second == id ? state.comparisons.erase(it)
                                                         : std::next(it);
  }
  state.global.erase(id);
  state.placed_by.erase(id);
  state.chained_alpha.erase(id);
  state.recent.erase(id);
  state.ungrouped.erase(std::remove(state.ungrouped.begin(), state.ungrouped.end(), id),
                        state.ungrouped.end());
  state.planes.erase(id);
  state.map_changed = true;
}

// The second evaluation of §II.F: members whose comparisons in the group are too short are
// taken out; one in no other group is placed into another group or dropped.
void RegroupMembers(MapperState& state, size_t g, int64_t now, const MapperOptions& options) {
  Group& group = state.groups[g];
  if (group.members.size() < 2) return;
  // Pairs never compared since they were grouped (one left the view first) are compared now
  // over what both observed: the interval they really share.
  const std::vector<int64_t> members = group.members;
  for (size_t i = 0; i < members.size(); ++i) {
    for (size_t j = i + 1; j < members.size(); ++j) {
      if (state.FindComparison(members[i], members[j]) == nullptr &&
          CommonSince(*state.Plane(members[i]), *state.Plane(members[j]), INT64_MIN) > 0) {
        const PairKey key = KeyOf(members[i], members[j]);
        state.comparisons.try_emplace(key, key.first, key.second)
            .first->second.Update(*state.Plane(key.first), *state.Plane(key.second), now,
                                  options.comparison, options.registration.last_seen_window);
      }
    }
  }
  std::vector<int64_t> short_lived;
  for (int64_t m : members) {
    if (MemberInterval(state, group, m) < options.regrouping.min_interval) short_lived.push_back(m);
  }
  for (int64_t id : short_lived) {
    Leave(state, group, id);
    if (!state.Plane(id)->groups.empty()) continue;  // another group still places it
    if (!JoinAnother(state, g, id, now, options)) DropPlane(state, id);
  }
}

}  // namespace

int64_t ObservationHorizon(const MapperOptions& options) {
  return options.regrouping.freeze_after + options.grouping.covisible_window;
}

void Regroup(MapperState& state, int64_t now, const MapperOptions& options) {
  const RegroupingOptions& o = options.regrouping;
  for (size_t g = state.open_from; g < state.groups.size(); ++g) {
    Group& group = state.groups[g];
    const int64_t age = now - group.created;
    if (o.enabled && group.stage == GroupStage::kNew && age >= o.reorder_after) {
      group.order = ChooseOrder(group, state, options.comparison);
      group.stage = GroupStage::kReordered;
      group.dirty = true;
    }
    if (o.enabled && group.stage == GroupStage::kReordered && age >= o.regroup_after) {
      RegroupMembers(state, g, now, options);
      group.order = ChooseOrder(group, state, options.comparison);
      group.stage = GroupStage::kRegrouped;
      group.dirty = true;
    }
    // Past the horizon the relative map is frozen (built once more if dirty): the
    // observations it came from are about to be dropped, and a re-seen group costs nothing.
    if (group.stage != GroupStage::kFrozen && age >= o.freeze_after) {
      group.stage = GroupStage::kFrozen;
    }
  }
  while (state.open_from < state.groups.size() && state.groups[state.open_from].Frozen()) {
    ++state.open_from;
  }
}

void DropOldObservations(MapperState& state, const std::vector<int64_t>& visible, int64_t now,
                         const MapperOptions& options) {
  const int64_t before = now - ObservationHorizon(options);
  for (int64_t id : visible) {
    if (RltPlane* plane = state.Plane(id)) plane->DropBefore(before);
  }
  // Planes out of view keep theirs until the next sweep.
  if (state.last_sweep >= 0 && now - state.last_sweep < options.regrouping.sweep_period) return;
  state.last_sweep = now;
  for (auto& [id, plane] : state.planes) plane.DropBefore(before);
}

}  // namespace relplane::mapper
