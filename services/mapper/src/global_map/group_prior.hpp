#pragma once
// §II.D a group's prior: the group's members as seen around when it was made, kept in the
// group so it can be placed again once their observations are dropped (§II.F storage). Internal
// to the mapper library: global_map.cpp places the groups with it.

#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "global_map/inputs.hpp"
#include "global_map/placement.hpp"
#include "grouping/group.hpp"
#include "plane_store/observation.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// One member's line in a group's prior: a point on it as seen around when the group was made,
// in the world, and the member's place in the relative map.
struct PriorLine {
  Eigen::Vector2d seen_point = Eigen::Vector2d::Zero();
  Placement member;
  double length = 0.0;  // m, the member's length (RltPlane::Length)
};

// A group's prior (§II.D): a placement, and the lines of the members known by more than their
// orientation as seen around when the group was made, which decide every direction they span.
struct Prior {
  geometry::Pose2 pose;
  std::vector<PriorLine> lines;
};

// The pose estimated at `iteration`, or the start pose when there is none.
geometry::Pose2 PoseAt(const GlobalMapInputs& in, int64_t iteration, const MapperOptions& options);

// Member `id` of `group`, known by its orientation only, as its sightings from poses the walls
// fixed agree on its line, kept in the group. One sighting does not place it (§II.A end): a wall
// seen edge-on through a door, over 0.1 to 0.5 m, is fitted up to 6 degrees off, and its first
// sighting, 1.6 degrees off, left it 1.4 degrees off on the map for good. Its orientation is the
// mean of theirs weighted by how well each fit fixes it (OrientationWeight, as localisation
// weighs them), its line through the mean of their middles weighted by how well each fixes its
// offset. Also the sightings since the group was made: a member that joined later has none
// before (placing a wall's line from a pose is §II.A's "transformed using current position").
// Falls back to the sighting when the group was made when fewer than two agree.
SeenWall LineWhenMade(const GlobalMapInputs& in, Group& group, int64_t id,
                      const MapperOptions& options);

// Were the samples at end `ref` of `seen` further apart than the end's own noise (2 sigma,
// LocalisationOptions::edge_noise)? The last sample on the wall is then centimetres short of the
// end.
bool CoarselySampled(const GlobalMapInputs& in, const SeenWall& seen, int ref,
                     const MapperOptions& options);

// PriorPlacement, with its members' lines as seen to decide the directions they span. A wall's
// line is fitted to all its points, while an end is where the sensor's last ray met the wall,
// short of it by up to the rays' spacing along the wall, which grows as they graze it (§II.C).
// PriorPlacement's placement comes from one reference end, so across the walls it carries that
// end's sampling error, or its sighting's heading error times the end's distance from them: a
// pilaster's group is put centimetres along the hallway from an end, where the pilaster's face,
// seen square on, puts it within millimetres. The basis's line alone leaves the other direction
// to an end: a room linked to the rooms before by orientation only moves centimetres across its
// outer wall when its basis changes from that wall to a partition beside it whose end, seen far
// off, is sampled short.
// `previous`: the group's members known by a point, as its last build placed them in the world
// (empty before its first).
Prior PriorWithMemberLines(const GlobalMapInputs& in, const std::map<int64_t, Placement>& previous,
                           Group& group, const MapperOptions& options);

}  // namespace relplane::mapper
