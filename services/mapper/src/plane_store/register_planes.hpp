#pragma once
// §II.A the registration step: each plane of the iteration matched to an rltplane (the latest
// untransformed sighting, RegisterObservations), else to the global map from the pose the matched
// walls give (backtracking, MatchGlobal), else made a new rltplane; a re-seen old wall notes a
// loop closing (global_map/loop_closure.hpp).

#include <cstdint>
#include <vector>

#include "global_map/loop_closure.hpp"
#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "localisation/frustum.hpp"
#include "motion/motion_model.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/observation.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/mapper/options.hpp"

namespace relplane::mapper {

// What registration is given of the iteration.
struct RegistrationFrame {
  int64_t iteration = 0;
  int64_t previous_iteration = -1;  // the iteration before, -1 at the first
  geometry::Pose2 previous_pose;    // its pose
  Motion motion;                    // the motion model's prediction for this iteration
  int held = 0;                     // Localiser::Held() before this iteration
};

struct Registered {
  std::vector<int64_t> visible;  // the rltplanes seen now, sorted
  std::vector<int64_t>
      created;       // the new rltplanes among them, in the order made: ungrouped (§II.B)
  ClosingLoop loop;  // a loop closing at this iteration, if any
};

// Adds the observations (consumed) to the plane store (planes, recent, next_id); the new rltplanes
// are returned for the grouping step's ungrouped list (§II.B).
Registered RegisterPlanes(const RegistrationFrame& frame, std::vector<Observation>& observations,
                          const LearnedFrustum& frustum, const MotionModel& motion,
                          const MapperOptions& options, const Grouping& grouping,
                          const WorldMap& world, const Trajectory& trajectory, PlaneStore& store);

// Each plane seen now keeps the pose it was last seen from, and its first sighting from a known
// pose (§II.D: a group is placed from its members' sightings).
void NoteSightingPose(const std::vector<int64_t>& visible, const geometry::Pose2& pose,
                      PlaneStore& store);

}  // namespace relplane::mapper
