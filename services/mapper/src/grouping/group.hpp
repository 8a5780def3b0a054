#pragma once
// A group of rltplanes (§II.B) and the set of them the grouping step owns (§II.B, §II.F).

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "global_map/placement.hpp"
#include "plane_store/rltplane.hpp"
#include "relplane/common/geometry.hpp"

namespace relplane::mapper {

// Where a group is in §II.F: new (order chosen afresh at every build), reordered (order kept),
// regrouped (short-interval members taken out), frozen (relative map kept, never rebuilt: its
// members' old observations are gone).
enum class GroupStage : int { kNew = 0, kReordered = 1, kRegrouped = 2, kFrozen = 3 };

// §II.B a group of rltplanes seen in the same time interval.
struct Group {
  int64_t id = 0;
  std::vector<int64_t> members;  // in joining order
  int64_t created = 0;           // iteration
  GroupStage stage = GroupStage::kNew;
  ChainOrder order;  // kept from the reordering on (§II.F)
  RelativeMap relative;
  geometry::Pose2 placement;  // world <- group frame (§II.D)
  // The placement hard chaining gave it when it was last placed (§II.D), which a pose graph
  // solve does not change: the centre of the group's prior in the graph (pose_graph.cpp).
  geometry::Pose2 chained;
  bool has_chained = false;
  // Members as seen when the group was made, from the pose then: the basis gives the prior
  // placement, a member placed by orientation only its line. Kept so the group can be placed
  // again after the observations are dropped.
  std::map<int64_t, SeenWall> seen;
  // Members as last seen before the group was made from a pose the walls fixed (invalid when
  // never so seen): the prior along a direction the links leave open (global_map.cpp).
  std::map<int64_t, SeenWall> seen_fixed;
  // Members placed by orientation only, their line as their sightings from poses the walls fixed
  // agree on it (global_map.cpp), with the plane's latest iteration then: kept for the same
  // reason as `seen`, and worked out again only when the plane was seen since.
  std::map<int64_t, std::pair<int64_t, SeenWall>> seen_line;
  // Whether a member's sighting (id, reference end, iteration) shows the wall's end, judged from
  // its sightings before the group was made (global_map.cpp): those do not change, and judging
  // them again at every build cost more than the rest of an iteration.
  std::map<std::tuple<int64_t, int, int64_t>, bool> shows_end;
  // Each member end's (id, reference end) most finely sampled sighting from a pose the walls
  // fixed (group_prior.cpp), with the iteration its observations were scanned to.
  struct FinestEnd {
    SeenWall seen;
    double spacing = 0.0;  // m between the sensor's samples along the wall at that end
    int64_t scanned = -1;  // iteration
    SeenWall previous;     // the last sighting from a fixed pose scanned
  };
  std::map<std::pair<int64_t, int>, FinestEnd> finest_end;
  bool dirty = true;
  int loop_evidence = 0;  // GroupLoopEvidence when last placed (pose_graph.hpp)

  bool Frozen() const { return stage == GroupStage::kFrozen; }
};

// The groups, owned by the grouping step (§II.B, §II.F); the other steps read them, and the
// global map writes only each group's placement and caches (global_map/).
struct Grouping {
  std::vector<Group> groups;       // index == id
  std::vector<int64_t> ungrouped;  // §II.B ungrouped list, oldest first
  size_t open_from = 0;            // groups before this index are frozen (§II.F)

  // Groups whose relative map is to be built again (§II.D).
  void MarkDirty(const std::set<int64_t>& ids) {
    for (int64_t g : ids) groups[static_cast<size_t>(g)].dirty = true;
  }
  // Rltplane `id` left the map (§II.F): it is no longer waiting for a group.
  void Forget(int64_t id) {
    ungrouped.erase(std::remove(ungrouped.begin(), ungrouped.end(), id), ungrouped.end());
  }
};

}  // namespace relplane::mapper
