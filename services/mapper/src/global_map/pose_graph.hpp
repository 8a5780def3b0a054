#pragma once
// Soft-linked groups (the paper's future work, §V): instead of chaining each group hard to the
// global map through its link planes, the groups are nodes of a graph of relative transforms.
// Two groups that hold the same rltplane are tied by it: the plane's placement in each group's
// relative map must agree in the world (orientation, line and, where both know it, the static
// edge). Consecutive groups give the chain; a rltplane re-seen after a loop (§II.A end
// backtracking) ties the closing group to an old one. Least squares over the group basis poses
// spreads the error a closed loop reveals over the whole loop, and a plane removed from a group
// only removes one tie: the other ties and a weak prior keep the group placed.

#include <cstdint>

#include "global_map/inputs.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// Ties of group `g` to earlier groups through shared rltplanes that skip at least `min_span`
// groups: loop closures. Counted with the weight of what the two placements know, so the sum
// over the groups grows both when a loop closes and when a closing tie learns more.
int GroupLoopEvidence(const PlaneStore& store, const Grouping& grouping, size_t g, int min_span);

struct PoseGraphResult {
  int iterations = 0;
  int ties = 0;
  double cost_before = 0.0;  // sum of squared normalised residuals
  double cost_after = 0.0;
  // No loop closed by backtracking, and every tie held within PoseGraphOptions::consistent
  // sigmas by the chained placements: no solve, the groups were put back where the chain
  // placed them.
  bool consistent = false;
};

// Gauss-Newton over all group placements (world <- group frame), starting from the current
// ones; group 0 stays where it is (anchored at the start pose, §II.D). None where the chained
// placements already hold every tie and no loop closed by backtracking
// (PoseGraphResult::consistent).
PoseGraphResult OptimiseGroupPlacements(const GlobalMapInputs& in, const WorldMap& world,
                                        const MapperOptions& options, Grouping& grouping);

}  // namespace relplane::mapper
