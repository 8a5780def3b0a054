#pragma once
// Groups, placements and sightings built by hand, for the tests of placing groups on the global
// map and of a group's prior (§II.D).

#include <Eigen/Core>
#include <cstdint>
#include <map>

#include "ideal_segmenter.hpp"
#include "plane_store/observation.hpp"
#include "relplane/common/geometry.hpp"
#include "state.hpp"

namespace relplane::mapper::testing {

inline Placement Placed(double alpha, const Eigen::Vector2d& point, int ref, Known known) {
  Placement p;
  p.alpha = alpha, p.point = point, p.ref = ref, p.known = known;
  return p;
}

// A group whose relative map is built (not dirty): its members and their relative placements,
// the first one the basis.
inline Group Built(int64_t id, int64_t created, const std::map<int64_t, Placement>& relative,
                   int64_t basis) {
  Group group;
  group.id = id;
  group.created = created;
  for (const auto& [member, placed] : relative) group.members.push_back(member);
  group.dirty = false;
  group.relative.basis = basis;
  group.relative.members = relative;
  return group;
}

// The part [s0, s1] (metres from `a` towards `b`) of the wall a-b seen from `pose`.
inline Observation PartSeen(const geometry::Pose2& pose, const Eigen::Vector2d& a,
                            const Eigen::Vector2d& b, double s0, double s1, int64_t iteration) {
  const geometry::Pose2 inv = pose.Inverse();
  const Eigen::Vector2d t = (b - a).normalized();
  return *MakeObservation(WallSeen(inv * (a + s0 * t), inv * (a + s1 * t)), iteration, 0.3);
}

// A wall from a to b as seen from (x, 0) facing along x, at iteration k.
inline Observation SeenAlongX(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double x,
                              int64_t k) {
  return *MakeObservation(testing::WallSeen(a - Eigen::Vector2d(x, 0), b - Eigen::Vector2d(x, 0)),
                          k, 0.3);
}

}  // namespace relplane::mapper::testing
