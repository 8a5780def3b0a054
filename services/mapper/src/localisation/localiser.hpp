#pragma once
// §II.D the iteration's pose from the walls in view against the global map, with the §II.E
// motion model where they leave a direction open; before the first group, the walls as first
// seen from the start pose.

#include <cstdint>
#include <vector>

#include "global_map/world_map.hpp"
#include "localisation/frustum.hpp"
#include "localisation/pose_solver.hpp"
#include "motion/motion_model.hpp"
#include "motion/trajectory.hpp"
#include "plane_store/plane_store.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

// What the localiser is given of the iteration (it owns none of it).
struct LocaliserFrame {
  int64_t iteration = 0;
  int64_t previous_iteration = -1;  // the iteration before, -1 at the first
  geometry::Pose2 previous_pose;    // its pose (the start pose at the first)
  Motion motion;                    // the motion model's prediction for this iteration
  const std::vector<int64_t>* visible = nullptr;  // rltplanes seen now, sorted
  int64_t first_iteration = -1;                   // the start pose's iteration
};

class Localiser {
 public:
  explicit Localiser(const MapperOptions& options);

  PoseEstimate Localise(const LocaliserFrame& frame, const PlaneStore& store, const WorldMap& world,
                        const Trajectory& trajectory, const LearnedFrustum& frustum,
                        const MotionModel& motion);

  // Iterations in a row whose position was held still: no motion known, the walls leaving the
  // heading open and no wall end moving it (the pose solver's `held`).
  int Held() const { return held_; }

 private:
  // The walls in view that the map places (or, before the first group, that were seen from the
  // start pose), as sightings for the pose solver.
  std::vector<Sighting> Sightings(const LocaliserFrame& frame, const PlaneStore& store,
                                  const WorldMap& world, bool initializing) const;

  LocalisationOptions options_;
  FitOptions fit_;
  int max_coast_;
  geometry::Pose2 start_;
  int held_ = 0;
  int64_t last_walled_ = -1;  // the last iteration whose pose mapped walls placed
  // rad per iteration: how far a heading may turn in an iteration beyond the motion model's turn
  // (MotionOptions::turn_rate), the heading prior's growth.
  double turn_rate_;
  double heading_sigma_ = 0.0;  // rad: the last iteration's heading error (0: none yet)
};

}  // namespace relplane::mapper
