#include "localisation/localiser.hpp"

#include <cmath>

#include "global_map/global_map.hpp"

namespace relplane::mapper {

Localiser::Localiser(const MapperOptions& options)
    : options_(options.localisation),
      fit_(options.fit),
      max_coast_(options.motion.max_coast),
      start_{options.start_pose.x, options.start_pose.y, options.start_pose.yaw},
      turn_rate_(options.motion.turn_rate) {}

std::vector<Sighting> Localiser::Sightings(const LocaliserFrame& frame, const PlaneStore& store,
                                           const WorldMap& world, bool initializing) const {
  std::vector<Sighting> sightings;
  for (int64_t id : *frame.visible) {
    const RltPlane* plane = store.Plane(id);
    if (plane == nullptr || plane->LastSeen() != frame.iteration) continue;
    if (!initializing) {
      auto it = world.global.find(id);
      if (it != world.global.end()) sightings.push_back({&plane->Latest(), plane, it->second});
    } else if (plane->FirstSeen() == frame.first_iteration) {
      // Before the first group: the walls' lines as first seen from the start pose.
      sightings.push_back(
          {&plane->Latest(), plane, PlacementOf(plane->Observations().front(), start_, -1)});
    }
  }
  return sightings;
}

PoseEstimate Localiser::Localise(const LocaliserFrame& frame, const PlaneStore& store,
                                 const WorldMap& world, const Trajectory& trajectory,
                                 const LearnedFrustum& frustum, const MotionModel& motion) {
  const int64_t iteration = frame.iteration;
  const bool initializing = world.global.empty();
  std::vector<Sighting> sightings = Sightings(frame, store, world, initializing);
  const bool motion_known = frame.motion.known;
  const std::set<int64_t>& fixed = trajectory.fixed;
  // How far off the prediction may be: odometry says so itself; a learnt velocity drifts with
  // the iterations since the walls last fixed the position.
  const Prediction prediction =
      frame.motion.odometry ? Prediction{true, frame.motion.sigma}
      : motion_known && !fixed.empty()
          ? LearntVelocity(static_cast<int>(iteration - *fixed.rbegin()), options_)
          : Prediction{};
  // §II.E the heading the motion model expects: the last one turned on at the rate of a turn on
  // the spot, its error grown by up to a turn_rate an iteration (a heading that is not turning
  // on the spot turns less).
  HeadingPrior heading_prior;
  if (!initializing && frame.previous_iteration >= 0 && heading_sigma_ > 0.0) {
    const double iterations = static_cast<double>(iteration - frame.previous_iteration);
    heading_prior.yaw = frame.motion.predicted.yaw + frame.motion.yaw_rate * iterations;
    heading_prior.sigma = std::hypot(heading_sigma_, turn_rate_ * iterations);
  }
  bool ends_seen = false;
  auto localise = [&](const geometry::Pose2& previous) {
    PoseEstimate est = mapper::Localise(sightings, previous, frustum, options_, fit_, held_,
                                        prediction, heading_prior);
    if (est.status != PoseStatus::kMotionModel || motion_known || ends_seen) return est;
    // The walls leave a direction open and the motion is not known (the start, moving off
    // after a turn on the spot; not while turning): the wall ends seen from poses the walls fixed
    // may show the motion along it (§II.E). Not where the motion is known: an end seen from
    // another place is off along its wall by centimetres, which the learnt velocity is not.
    // Looked up only then, as it goes through every kept observation of the walls in view.
    ends_seen = true;
    for (Sighting& x : sightings) {
      for (int e = 0; e < 2; ++e) {
        const SeenWall seen = EndSeenFromFixedPoses(trajectory, *x.plane, e);
        x.end_seen[e] = seen.valid;
        if (seen.valid) x.end[e] = seen.edge[e];
      }
    }
    return mapper::Localise(sightings, previous, frustum, options_, fit_, held_, {}, heading_prior);
  };
  PoseEstimate estimate = localise(frame.motion.predicted);
  // Odometry knows whether the sensor moved on while it turned; a learnt velocity does not.
  if (!frame.motion.odometry && frame.previous_iteration >= 0 &&
      motion.Turning(frame.previous_pose, estimate.pose, iteration - frame.previous_iteration,
                     estimate.yaw_sigma)) {
    // The turn starts now: the sensor did not walk on after all.
    estimate = localise(frame.previous_pose);
  }
  if (!initializing && estimate.planes > 0) last_walled_ = iteration;
  if (estimate.status == PoseStatus::kLost && sightings.empty() && !initializing &&
      last_walled_ >= 0 && iteration - last_walled_ <= max_coast_) {
    // No mapped wall in view for a moment (a wall's two pieces beside a door reported as one,
    // registered to neither): the pose solver kept the pose it started from, the motion
    // model's (§II.E). That is a pose, not LOST; not where walls were in view and disagreed,
    // nor for long.
    estimate.status = PoseStatus::kMotionModel;
  }
  const bool held =
      !motion_known && estimate.status == PoseStatus::kMotionModel && !estimate.end_moved;
  held_ = held ? held_ + 1 : 0;
  // The next prior starts from this heading's error; with no wall in view, from this prior's.
  heading_sigma_ =
      estimate.planes > 0 && estimate.yaw_sigma > 0.0 ? estimate.yaw_sigma : heading_prior.sigma;
  if (initializing) estimate.status = PoseStatus::kInitializing;
  if (frame.first_iteration == iteration) estimate.pose = frame.previous_pose;
  return estimate;
}

}  // namespace relplane::mapper
