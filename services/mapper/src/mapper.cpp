#include "relplane/mapper/mapper.hpp"

#include <limits>
#include <utility>

#include "comparison/compare_visible.hpp"
#include "global_map/build_maps.hpp"
#include "global_map/loop_closure.hpp"
#include "grouping/grouping.hpp"
#include "grouping/regrouping.hpp"
#include "localisation/frustum.hpp"
#include "localisation/localiser.hpp"
#include "motion/motion_model.hpp"
#include "plane_store/register_planes.hpp"
#include "plane_store/sensing.hpp"
#include "plane_store/view_cuts.hpp"
#include "published_map/published_map.hpp"
#include "state.hpp"

namespace relplane::mapper {

// The components and what the facade keeps of the frame sequence.
struct Mapper::Steps {
  explicit Steps(const MapperOptions& options)
      : frustum(options),
        motion(options.motion, options.localisation.max_step),
        localiser(options),
        pose{options.start_pose.x, options.start_pose.y, options.start_pose.yaw} {}

  MapperState state;
  LearnedFrustum frustum;
  MotionModel motion;
  Localiser localiser;
  geometry::Pose2 pose;  // the last iteration's pose (the start pose before the first)
  int64_t last_iteration = -1;
  // The frustum's range limit the stored edges were last judged against (MarkViewCuts).
  double judged_range_limit = std::numeric_limits<double>::infinity();
  // The angular step the stored edges were last judged coarse against (MarkViewCuts).
  double judged_step = 0.0;
  // Odometry read since the last pose the walls fixed (`anchor`, when `anchored`), in that
  // pose's frame: the span MotionModel::CalibrateOdometry learns odometry's scale from.
  bool anchored = false;
  geometry::Pose2 anchor;
  geometry::Pose2 driven;
};

Mapper::Mapper(MapperOptions options)
    : options_(std::move(options)), steps_(std::make_unique<Steps>(options_)) {}
Mapper::~Mapper() = default;
Mapper::Mapper(Mapper&&) noexcept = default;
Mapper& Mapper::operator=(Mapper&&) noexcept = default;

PoseEstimate Mapper::Process(int64_t iteration, const std::vector<PlaneInput>& planes,
                             const std::optional<OdometryIncrement>& odometry) {
  Steps& s = *steps_;
  MapperState& state = s.state;
  if (iteration <= s.last_iteration) return {s.pose, PoseStatus::kLost, 0};
  if (state.first_iteration < 0) {  // the start pose anchors the map
    state.first_iteration = iteration;
    state.trajectory.Record(iteration, s.pose, true);
  }
  // §II.E the motion since the last iteration: wheel odometry's where the robot has it, else
  // the velocity learnt from the poses the walls fixed.
  // An increment farther than the platform moves in the iterations it spans is not motion (a
  // reset odometry frame, a bad message): refused, and said in the pose.
  const bool odometry_refused =
      odometry && s.last_iteration >= 0 &&
      !(odometry->motion.Translation().norm() <=
        options_.localisation.max_step * static_cast<double>(iteration - s.last_iteration));
  const Motion motion =
      odometry && s.last_iteration >= 0 && !odometry_refused
          ? s.motion.Odometry(s.pose, *odometry)
          : s.motion.Predict(state.trajectory, s.pose, s.last_iteration, iteration);
  const int64_t previous = s.last_iteration;
  s.last_iteration = iteration;

  // §II.A the planes as wall observations, their edges cut by the view as it is learnt.
  std::vector<Observation> observations =
      Observe(iteration, planes, options_.registration, options_.comparison.static_std, &s.frustum);
  if (s.frustum.RangeLimit() < s.judged_range_limit || s.frustum.AngularStep() != s.judged_step) {
    s.judged_range_limit = s.frustum.RangeLimit();
    s.judged_step = s.frustum.AngularStep();
    MarkViewCuts(s.frustum, options_.comparison.static_std, state.store, state.grouping);
  }

  const RegistrationFrame frame{iteration, previous, s.pose, motion, s.localiser.Held()};
  // §II.A each plane to its rltplane, to the global map's (backtracking), or a new one.
  const Registered registered =
      RegisterPlanes(frame, observations, s.frustum, s.motion, options_, state.grouping,
                     state.world, state.trajectory, state.store);
  const std::vector<int64_t>& visible = registered.visible;
  // §II.B grouping, §II.F regrouping.
  UpdateGroups(registered.created, visible, iteration, options_.grouping, state.grouping,
               state.store);
  Regroup(iteration, options_, state.grouping, state.store, state.comparisons, state.world);
  // §II.C the comparisons; the groups they changed are built again (§II.D).
  state.grouping.MarkDirty(
      CompareVisible(iteration, visible, options_, state.grouping, state.store, state.comparisons));
  // §II.D the next relative map, and the global map chained from it.
  BuildNextGlobalMap({state.store, state.comparisons, state.trajectory, state.first_iteration,
                      s.frustum.AngularStep()},
                     options_, state.grouping, state.world);
  // §II.D-E the pose from the global map, and the loop it closes (§II.A end).
  PoseEstimate estimate =
      s.localiser.Localise({iteration, previous, s.pose, motion, &visible, state.first_iteration},
                           state.store, state.world, state.trajectory, s.frustum, s.motion);
  AddPoseTie(registered.loop, estimate, options_.graph, state.grouping, state.world);
  estimate.odometry_refused = odometry_refused;

  const bool fixed = estimate.status == PoseStatus::kTracking;
  state.trajectory.Record(iteration, estimate.pose, fixed);  // §II.E
  if (fixed) s.motion.Fixed();
  // Odometry's scale from the spans between fixed poses it read without a break.
  const bool read = odometry && !odometry_refused && previous >= 0;
  if (read && s.anchored) s.driven = s.driven * odometry->motion;
  if (!read) s.anchored = false;
  if (fixed && (!s.anchored || s.motion.CalibrateOdometry(s.anchor, estimate.pose, s.driven))) {
    s.anchored = true, s.anchor = estimate.pose, s.driven = geometry::Pose2{};
  }
  s.pose = estimate.pose;
  NoteSightingPose(visible, s.pose, state.store);
  DropOldObservations(visible, iteration, options_, state.store);  // bounded memory (§II.F)
  state.trajectory.ForgetBefore(iteration - options_.motion.pose_history);
  return estimate;
}

bool Mapper::TakeMapChanged() {
  const bool changed = steps_->state.world.changed;
  steps_->state.world.changed = false;
  return changed;
}

MapSnapshot Mapper::Map() const { return PublishedMap(steps_->state, options_); }

MapperStats Mapper::Stats() const {
  const MapperState& state = steps_->state;
  MapperStats stats;
  stats.planes = state.store.planes.size();
  for (const auto& [id, plane] : state.store.planes)
    stats.observations += plane.Observations().size();
  stats.comparisons = state.comparisons.pairs.size();
  stats.groups = state.grouping.groups.size();
  stats.map_planes = state.world.global.size();
  stats.graph_solves = state.world.graph_solves;
  return stats;
}

const MapperState& Mapper::State() const { return steps_->state; }

}  // namespace relplane::mapper
