#pragma once
// §II.E the sensor's path as the mapper estimated it: each iteration's pose, and which of them
// the walls fixed in every direction (tracking, §II.D).

#include <cstdint>
#include <map>
#include <set>

#include "relplane/common/geometry.hpp"

namespace relplane::mapper {

struct Trajectory {
  std::map<int64_t, geometry::Pose2> poses;  // iteration -> estimated pose (recent only)
  // Iterations of `poses` the walls fixed in every direction (tracking, §II.D), and the first
  // iteration's (the anchor). Elsewhere the motion model kept a direction at its old value
  // while the sensor moved on (§II.E), so a wall placed from that pose is off along it.
  std::set<int64_t> fixed;

  void Record(int64_t iteration, const geometry::Pose2& pose, bool is_fixed) {
    poses[iteration] = pose;
    if (is_fixed) fixed.insert(iteration);
  }
  // Bounded memory: poses before `iteration` are dropped.
  void ForgetBefore(int64_t iteration) {
    while (!poses.empty() && poses.begin()->first < iteration) poses.erase(poses.begin());
    while (!fixed.empty() && *fixed.begin() < iteration) fixed.erase(fixed.begin());
  }
};

}  // namespace relplane::mapper
