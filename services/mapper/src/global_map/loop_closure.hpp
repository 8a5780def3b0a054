#pragma once
// A loop closing through backtracking (§II.A end): at one iteration the walls in view, placed by
// the drifting chain, put the sensor at one pose and the re-seen old walls at another. Noted at
// registration, made a PoseTie (world_map.hpp) for the pose graph once the iteration's pose is
// known, so the error the loop reveals is spread over the groups between them.

#include <cstdint>
#include <vector>

#include "global_map/world_map.hpp"
#include "grouping/group.hpp"
#include "localisation/pose_solver.hpp"
#include "motion/motion_model.hpp"
#include "motion/trajectory.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

struct ClosingLoop {
  bool closing = false;
  geometry::Pose2 pose;  // the sensor pose from the chain's walls alone
  int64_t from = -1;     // the chain's newest group among the walls in view
  int64_t to = -1;       // the oldest group among the re-seen walls
  bool open = false;     // the chain's walls left the direction open_alpha (world) open
  double open_alpha = 0.0;
};

// The loop closing where walls of group `oldest` were matched again while `chain`, the walls in
// view registered as usual, put the sensor at `pose`: a closing only where all of `chain` was
// placed by groups well after `oldest` (`grouping.recent_groups`), and the chain's walls fix at
// least one direction (or the sensor turns on the spot). `previous_pose` is the pose of
// `previous_iteration`, the iteration before this one.
ClosingLoop NoteClosing(const std::vector<Sighting>& chain, const geometry::Pose2& pose,
                        int64_t oldest, const WorldMap& world, const Trajectory& trajectory,
                        const MotionModel& motion, int64_t previous_iteration,
                        const geometry::Pose2& previous_pose, const MapperOptions& options);

// The PoseTie of `loop` (if it closes), from the pose `estimate` found this iteration, added to
// world.pose_ties when the loop moved the pose by something (`options`). Returns whether a tie
// was added.
bool AddPoseTie(const ClosingLoop& loop, const PoseEstimate& estimate,
                const PoseGraphOptions& options, const Grouping& grouping, WorldMap& world);

}  // namespace relplane::mapper
