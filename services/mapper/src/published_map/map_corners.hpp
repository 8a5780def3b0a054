#pragma once
// §II.D end, on the published map: a wall's end drawn at the corner it meets, not at its last
// sample.

#include <Eigen/Core>
#include <vector>

#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

// A wall seen from above: its line n . p + d = 0 (unit n) and its two ends on that line.
struct WallSegment {
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double d = 0.0;
  Eigen::Vector2d end[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
};

// Moves a wall's end onto the line of a crossing wall (over 30° off) when that line passes
// within `radius` of the end and the crossing wall reaches the meeting point (to within
// `radius`). A wall is sampled by rays, so its last sample lies up to a ray spacing short of
// where it meets the next wall (3 cm at 4 m for a 160-ray, 90° sensor, 7-9 cm along a wall seen
// at a grazing angle 5 m away); both walls' lines are fitted over all their points, and where
// they cross is the corner itself. Of several crossing walls the nearest line wins; every move
// is worked out on the walls as given, so the result does not depend on their order. Walls
// shorter than 2 radii are only lengthened (the line crossing a short piece may be another
// surface's) unless the crossing wall ends there too (an L corner), and an end is cut back by
// at most a quarter of its wall (a line through its middle is not its corner). A radius of 0
// moves nothing. Returns how many ends moved.
int SnapSegmentEnds(std::vector<WallSegment>* walls, double radius,
                    const PublishedMapOptions& options = {});

// SnapSegmentEnds on the published map's walls (the planes with four vertices in Mapper::Map's
// order and a horizontal normal).
int SnapEndsToCorners(std::vector<MappedPlane>* planes, double radius,
                      const PublishedMapOptions& options = {});

}  // namespace relplane::mapper
