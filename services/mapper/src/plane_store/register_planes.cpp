#include "plane_store/register_planes.hpp"

#include <algorithm>
#include <set>
#include <utility>

#include "localisation/pose_solver.hpp"
#include "plane_store/backtracking.hpp"
#include "plane_store/registration.hpp"

namespace relplane::mapper {
namespace {

// §II.A compares each plane with a rltplane's latest sighting untransformed, which holds from one
// iteration to the next but not over a few while turning; a match must also hold from the pose
// now, as far as it is known: the last pose, turned on by the last iteration's turn while
// turning on the spot (at 0.8 rad/s a wall 4 m away moves 0.1 m along itself per iteration).
geometry::Pose2 PoseNow(const RegistrationFrame& frame, const Trajectory& trajectory,
                        const MotionModel& motion) {
  geometry::Pose2 now = frame.previous_pose;
  const auto last = trajectory.poses.find(frame.previous_iteration - 1);
  if (frame.previous_iteration == frame.iteration - 1 && last != trajectory.poses.end() &&
      motion.Turning(last->second, frame.previous_pose, 1)) {
    now.yaw =
        frame.previous_pose.yaw + geometry::WrapAngle(frame.previous_pose.yaw - last->second.yaw);
  }
  return now;
}

// §II.A end: unmatched planes are transformed with the current position (from the planes that
// did match) and compared to the global map before becoming new rltplanes. Fills `match` where
// the map has the wall; returns the loop closing this notes.
ClosingLoop Backtrack(const RegistrationFrame& frame, const std::vector<Observation>& observations,
                      const std::vector<int64_t>& also, const LearnedFrustum& frustum,
                      const MotionModel& motion, const MapperOptions& options,
                      const PlaneStore& store, const Grouping& grouping, const WorldMap& world,
                      const Trajectory& trajectory, std::vector<int64_t>* match_out) {
  std::vector<int64_t>& match = *match_out;
  std::vector<Sighting> sightings;
  for (size_t k = 0; k < observations.size(); ++k) {
    auto it = match[k] >= 0 ? world.global.find(match[k]) : world.global.end();
    if (it != world.global.end()) {
      sightings.push_back({&observations[k], store.Plane(match[k]), it->second});
    }
  }
  geometry::Pose2 pose = frame.motion.predicted;
  if (!sightings.empty()) {
    pose = Localise(sightings, frame.motion.predicted, frustum, options.localisation, options.fit,
                    frame.held)
               .pose;
  }
  std::set<int64_t> taken(match.begin(), match.end());
  taken.insert(also.begin(), also.end());
  int64_t oldest = -1;  // the oldest group placing a wall matched by backtracking
  for (size_t k = 0; k < observations.size(); ++k) {
    if (match[k] >= 0) continue;
    std::vector<const Observation*> others;
    for (size_t j = 0; j < observations.size(); ++j) {
      if (j != k) others.push_back(&observations[j]);
    }
    match[k] = MatchGlobal(observations[k], others, pose, store, grouping, world, trajectory, taken,
                           options.backtrack, options.fit);
    if (match[k] < 0) continue;
    taken.insert(match[k]);
    if (auto by = world.placed_by.find(match[k]); by != world.placed_by.end()) {
      oldest = oldest < 0 ? by->second : std::min(oldest, by->second);
    }
  }
  return NoteClosing(sightings, pose, oldest, world, trajectory, motion, frame.previous_iteration,
                     frame.previous_pose, options);
}

// The observations into the plane store: matched ones to their rltplanes, the rest as new ones.
Registered Store(std::vector<Observation>& observations, const std::vector<int64_t>& match,
                 const std::vector<int64_t>& also, const MapperOptions& options,
                 PlaneStore& store) {
  Registered out;
  std::vector<int64_t>& visible = out.visible;
  for (size_t k = 0; k < observations.size(); ++k) {
    if (match[k] >= 0 && also[k] >= 0) {
      store.Plane(also[k])->Add(Observation(observations[k]));  // both ends cut: no end to mark
      visible.push_back(also[k]);
    }
    if (match[k] >= 0) {
      store.Plane(match[k])->Add(std::move(observations[k]));
      visible.push_back(match[k]);
    } else {
      const int64_t id = store.next_id++;
      store.planes.emplace(
          id, RltPlane(id, std::move(observations[k]), options.comparison.phase_hysteresis,
                       options.max_observations, options.rltplane, options.fit));
      out.created.push_back(id);
      visible.push_back(id);
    }
  }
  return out;
}

// Recently seen rltplanes are the only registration candidates next time.
void UpdateRecent(int64_t iteration, const std::vector<int64_t>& visible,
                  const RegistrationOptions& options, PlaneStore& store) {
  store.recent.insert(visible.begin(), visible.end());
  for (auto it = store.recent.begin(); it != store.recent.end();) {
    const RltPlane* plane = store.Plane(*it);
    if (plane == nullptr || iteration - plane->LastSeen() >= options.last_seen_window) {
      it = store.recent.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace

Registered RegisterPlanes(const RegistrationFrame& frame, std::vector<Observation>& observations,
                          const LearnedFrustum& frustum, const MotionModel& motion,
                          const MapperOptions& options, const Grouping& grouping,
                          const WorldMap& world, const Trajectory& trajectory, PlaneStore& store) {
  geometry::Pose2 now = PoseNow(frame, trajectory, motion);
  std::vector<int64_t> also;  // a line's older rltplane, as well (RegisterObservations)
  ClosingLoop loop;
  std::vector<int64_t> match = RegisterObservations(observations, store, world, trajectory,
                                                    options.registration, &now, &also);
  if (std::find(match.begin(), match.end(), -1) != match.end() && !world.global.empty()) {
    loop = Backtrack(frame, observations, also, frustum, motion, options, store, grouping, world,
                     trajectory, &match);
  }
  // §II.C: an end seen far from where it last was is another end, not the wall's.
  MarkJumpedEnds(match, store, trajectory, frame.previous_pose, &observations,
                 options.registration);
  Registered out = Store(observations, match, also, options, store);
  out.loop = loop;
  UpdateRecent(frame.iteration, out.visible, options.registration, store);
  std::sort(out.visible.begin(), out.visible.end());
  return out;
}

void NoteSightingPose(const std::vector<int64_t>& visible, const geometry::Pose2& pose,
                      PlaneStore& store) {
  for (int64_t id : visible) {
    RltPlane* plane = store.Plane(id);
    if (plane == nullptr) continue;
    plane->latest_pose = pose;
    plane->latest_pose_known = true;
    if (!plane->first_seen.valid) plane->first_seen = SeenFrom(plane->Latest(), pose);
  }
}

}  // namespace relplane::mapper
