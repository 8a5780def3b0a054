#pragma once
// §II.D placing a group on the global map: the least squares for world <- group from the links
// (the rltplanes it shares with groups already placed, or for the first group, its members'
// first sightings) and the group's prior.

#include <cstdint>
#include <vector>

#include "global_map/group_prior.hpp"
#include "global_map/placement.hpp"
#include "plane_store/rltplane.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// One rltplane as the group places it (`relative`) and as the map already has it (`global`).
struct GroupLink {
  Placement relative;
  Placement global;
  const RltPlane* plane;
  // rad^-2: how well `global`'s orientation is known where it is one sighting (the first
  // group's); 0: as well as the plane's best fit (OrientationWeight).
  double orientation_weight = 0.0;
};

// The orientation weight of a plane's sighting at `iteration`: its fit's noise and, as a single
// fit is not averaged over an interval, a short piece's bias over its length (PieceBlur). 0 when
// the observation is gone.
double SightingOrientationWeight(const RltPlane& plane, int64_t iteration);

// Least squares for world <- group: rotation from the mean orientation difference, translation
// from the links' lines (1 equation each) and shared static edges (1 more along the wall).
geometry::Pose2 SolveGroupPlacement(const std::vector<GroupLink>& links, const Prior& prior,
                                    const MapperOptions& options);

}  // namespace relplane::mapper
