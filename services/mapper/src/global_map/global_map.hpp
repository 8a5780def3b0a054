#pragma once
// §II.D Global map: the first group is anchored at the start pose by comparing its relative map
// to its rltplanes' first observations (kept with each plane as SeenWall); every later group is
// placed through the rltplanes it shares with groups already placed (the link planes), and places
// its other members.

#include <cstddef>

#include "global_map/inputs.hpp"
#include "global_map/placement.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/rltplane.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// The placement of a wall observed as `obs` from sensor pose `pose`, with its point at edge
// `ref` (or, when ref < 0, at the middle of the part in view: a fit's line is as good as its
// points only where they are, and a door jamb's, a few degrees off, was 10 cm off at the foot of
// the perpendicular from the sensor).
Placement PlacementOf(const Observation& obs, const geometry::Pose2& pose, int ref);
// The same for a wall seen earlier, already in the world.
Placement PlacementOf(const SeenWall& seen, int ref);

// The latest sighting of `plane` from a pose the walls fixed that shows its end `ref` (not cut
// by the view), with that end moved to the median of all such sightings' (one outlier among
// them does not decide); invalid when there is none.
SeenWall EndSeenFromFixedPoses(const Trajectory& trajectory, const RltPlane& plane, int ref);

// The mapped wall's two ends (lo, hi along its direction): its static edges where known, else
// its length from the known one; for a wall known only by its line, the extent last seen, from
// the pose then.
void WallEnds(const Trajectory& trajectory, const RltPlane& plane, const Placement& placed,
              Eigen::Vector2d* lo, Eigen::Vector2d* hi);

// Re-places groups `from`, `from + 1`, ... (hard chaining: a change in one group moves every
// later one). Placements made by those groups are recomputed.
void BuildGlobalMap(const GlobalMapInputs& in, size_t from, const MapperOptions& options,
                    Grouping& grouping, WorldMap& world);

}  // namespace relplane::mapper
