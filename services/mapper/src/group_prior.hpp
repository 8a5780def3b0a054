#pragma once
// §II.D a group's prior: the group's members as seen around when it was made, kept in the
// group so it can be placed again once their observations are dropped (§II.F storage). Internal
// to the mapper library: global_map.cpp places the groups with it.

#include <cstddef>
#include <cstdint>

#include "relplane/common/geometry.hpp"
#include "relplane/mapper/observation.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/state.hpp"

namespace relplane::mapper {

// m: the first sighting's end and the latest one agree this well if they are the same end (edge
// noise and the pose's drift since the start).
constexpr double kFirstEndAgreement = 0.2;

// A group's prior (§II.D): a placement, and the basis's line as seen around when the group was
// made (when the basis is known by more than its orientation), with the basis's place in the
// relative map.
struct Prior {
  geometry::Pose2 pose;
  bool has_line = false;
  Eigen::Vector2d seen_point =
      Eigen::Vector2d::Zero();  // on the basis's line as seen, in the world
  Placement basis;
};

// The pose estimated at `iteration`, or the start pose when there is none.
geometry::Pose2 PoseAt(const MapperState& state, int64_t iteration, const MapperOptions& options);

// Member `id` of group `g`, known by its orientation only, as its sightings from poses the walls
// fixed agree on its line, kept in the group. One sighting does not place it (§II.A end): a wall
// seen edge-on through a door, over 0.1 to 0.5 m, is fitted up to 6 degrees off, and its first
// sighting, 1.6 degrees off, left it 1.4 degrees off on the map for good. Its orientation is the
// mean of theirs weighted by how well each fit fixes it (OrientationWeight, as localisation
// weighs them), its line through the mean of their middles weighted by how well each fixes its
// offset. Also the sightings since the group was made: a member that joined later has none
// before (placing a wall's line from a pose is §II.A's "transformed using current position").
// Falls back to the sighting when the group was made when fewer than two agree.
SeenWall LineWhenMade(MapperState& state, size_t g, int64_t id, const MapperOptions& options);

// PriorPlacement, with the basis's line as seen to decide the direction across the basis. A
// wall's line is fitted to all its points, while an end is where the sensor's last ray met the
// wall, short of it by up to the rays' spacing along the wall, which grows as they graze it
// (§II.C). PriorPlacement's placement comes from one reference end, so across the basis it
// carried that end's sampling error, or its sighting's heading error times the end's distance
// from the basis: a pilaster's group on loop_other_sensor was put 4 cm, then 8 cm, along the
// hallway, where the pilaster's face, seen square on, put it within 2 mm.
Prior PriorWithBasisLine(MapperState& state, size_t g, const MapperOptions& options);

}  // namespace relplane::mapper
