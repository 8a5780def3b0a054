// The steps as Mapper::Process calls them (§II.A-F), each on hand-built parts of the state: what
// a step writes of its own part, what it hands to the next one, and what it leaves alone.

#include <gtest/gtest.h>

#include "comparison/compare_visible.hpp"
#include "global_map/build_maps.hpp"
#include "grouping/regrouping.hpp"
#include "ideal_segmenter.hpp"
#include "localisation/localiser.hpp"
#include "plane_store/register_planes.hpp"
#include "state_parts.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

Observation Seen(int64_t k, Vector2d a, Vector2d b) {
  return *MakeObservation(testing::WallSeen(a, b), k, 0.3);
}

// Two walls of a room corner seen from the origin: one across the view, one along its left.
std::vector<Observation> Corner(int64_t k) {
  return {Seen(k, {3, -1}, {3, 1}), Seen(k, {0, 1}, {3, 1})};
}

RegistrationFrame FrameAt(int64_t k) {
  return {k, k == 0 ? -1 : k - 1, geometry::Pose2{}, Motion{}, 0};
}

TEST(StepCalls, RegistrationMakesNewRltplanesAndLeavesThemToGrouping) {
  const MapperOptions options;
  MapperState state;
  const LearnedFrustum frustum(options);
  const MotionModel motion(options.motion, options.localisation.max_step);
  std::vector<Observation> first = Corner(0);
  Registered r = RegisterPlanes(FrameAt(0), first, frustum, motion, options, state.grouping,
                                state.world, state.trajectory, state.store);
  EXPECT_EQ(r.created, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(r.visible, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(state.store.planes.size(), 2u);
  EXPECT_EQ(state.store.recent, (std::set<int64_t>{0, 1}));
  EXPECT_TRUE(state.grouping.ungrouped.empty());  // the grouping step's list (§II.B)

  // Seen again untransformed in the next iteration (§II.A): the same rltplanes, none new.
  std::vector<Observation> second = Corner(1);
  r = RegisterPlanes(FrameAt(1), second, frustum, motion, options, state.grouping, state.world,
                     state.trajectory, state.store);
  EXPECT_TRUE(r.created.empty());
  EXPECT_EQ(r.visible, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(state.store.Plane(0)->Count(), 2);
  EXPECT_EQ(state.store.Plane(1)->Count(), 2);
}

TEST(StepCalls, ComparisonNamesTheGroupsToRebuildAndLeavesFrozenOnesAlone) {
  const MapperOptions options;
  MapperState state;
  std::vector<Observation> seen = Corner(0);
  for (int64_t id = 0; id < 2; ++id) {
    state.store.planes.emplace(id, RltPlane(id, seen[static_cast<size_t>(id)], 0.05, 100));
    state.store.Plane(id)->groups = {0};
  }
  Group group;
  group.members = {0, 1};
  group.dirty = false;
  state.grouping.groups.push_back(group);

  const std::set<int64_t> rebuild =
      CompareVisible(0, {0, 1}, options, state.grouping, state.store, state.comparisons);
  EXPECT_EQ(rebuild, (std::set<int64_t>{0}));
  EXPECT_NE(state.comparisons.Find(1, 0), nullptr);
  EXPECT_FALSE(state.grouping.groups[0].dirty);  // Process marks it (Grouping::MarkDirty)
  // One plane in view: no pair to compare.
  EXPECT_TRUE(
      CompareVisible(1, {0}, options, state.grouping, state.store, state.comparisons).empty());
  // A frozen group keeps its relative map (§II.F); its comparisons still learn.
  state.grouping.groups[0].stage = GroupStage::kFrozen;
  for (int64_t id = 0; id < 2; ++id) state.store.Plane(id)->Add(Corner(2)[static_cast<size_t>(id)]);
  EXPECT_TRUE(
      CompareVisible(2, {0, 1}, options, state.grouping, state.store, state.comparisons).empty());
}

TEST(StepCalls, OldObservationsGoFromPlanesInViewAtOnceAndFromTheRestAtTheNextSweep) {
  const MapperOptions options;
  const int64_t horizon = ObservationHorizon(options);
  PlaneStore store;
  store.planes.emplace(0, RltPlane(0, Seen(10, {3, -1}, {3, 1}), 0.05, 10000));
  store.planes.emplace(1, RltPlane(1, Seen(50, {0, 1}, {3, 1}), 0.05, 10000));
  const int64_t now = 50 + horizon;
  store.Plane(0)->Add(Seen(now, {3, -1}, {3, 1}));
  store.Plane(1)->Add(Seen(now - 1, {0, 1}, {3, 1}));

  DropOldObservations({0}, now, options, store);         // the first sweep: every plane
  EXPECT_EQ(store.Plane(0)->Observations().size(), 1u);  // iteration 10 is past the horizon
  EXPECT_EQ(store.Plane(1)->Observations().size(), 2u);  // iteration 50 is not, yet

  const int64_t soon = now + 10;  // within the sweep period: only planes in view
  DropOldObservations({0}, soon, options, store);
  EXPECT_EQ(store.Plane(1)->Observations().size(), 2u);
  const int64_t swept = now + options.regrouping.sweep_period;
  DropOldObservations({0}, swept, options, store);
  EXPECT_EQ(store.Plane(1)->Observations().size(), 1u);
}

TEST(StepCalls, TheMapStepRebuildsFromTheFirstDirtyGroupOn) {
  const MapperOptions options;
  MapperState state;
  std::vector<Observation> seen = Corner(0);
  for (int64_t id = 0; id < 2; ++id) {
    state.store.planes.emplace(id, RltPlane(id, seen[static_cast<size_t>(id)], 0.05, 100));
  }
  state.first_iteration = 0;
  state.trajectory.Record(0, geometry::Pose2{}, true);
  for (int64_t g = 0; g < 2; ++g) {
    Group group;
    group.id = g;
    group.members = {0, 1};
    state.grouping.groups.push_back(group);
    for (int64_t id = 0; id < 2; ++id) state.store.Plane(id)->groups.push_back(g);
  }
  CompareVisible(0, {0, 1}, options, state.grouping, state.store, state.comparisons);

  // Group 1 alone out of date: group 0 is left as it is; group 1 is built and placed.
  state.grouping.groups[0].dirty = false;
  BuildNextGlobalMap(GlobalInputs(state), options, state.grouping, state.world);
  EXPECT_FALSE(state.grouping.groups[1].dirty);
  EXPECT_TRUE(state.grouping.groups[0].relative.members.empty());  // not built
  EXPECT_EQ(state.grouping.groups[1].relative.members.size(), 2u);
  EXPECT_TRUE(state.world.changed);
  // Both out of date: the chain is built again from group 0, and every later group with it
  // (hard chaining, §II.D: moving one group moves the ones after it).
  state.grouping.groups[0].dirty = state.grouping.groups[1].dirty = true;
  state.world.changed = false;
  BuildNextGlobalMap(GlobalInputs(state), options, state.grouping, state.world);
  EXPECT_FALSE(state.grouping.groups[0].dirty);
  EXPECT_FALSE(state.grouping.groups[1].dirty);
  EXPECT_EQ(state.world.global.size(), 2u);
  EXPECT_EQ(state.world.placed_by.at(0), 0);  // the first group to place a wall wins
  EXPECT_TRUE(state.world.changed);
}

Placement LineOf(const Observation& seen, const Vector2d& point) {
  Placement p;
  p.alpha = seen.Alpha();  // seen from the origin, yaw 0: the world's orientation
  p.point = point;
  p.known = Known::kLine;
  return p;
}

TEST(StepCalls, TheLocaliserTracksOnMappedWallsAndCoastsBrieflyWithoutThem) {
  MapperOptions options;
  PlaneStore store;
  WorldMap world;
  Trajectory trajectory;
  const LearnedFrustum frustum(options);
  const MotionModel motion(options.motion, options.localisation.max_step);
  Localiser localiser(options);

  // Before any group: walls first seen at the start iteration, placed from the start pose.
  std::vector<Observation> corner = Corner(0);
  for (int64_t id = 0; id < 2; ++id) {
    store.planes.emplace(id, RltPlane(id, corner[static_cast<size_t>(id)], 0.05, 100));
  }
  const std::vector<int64_t> visible = {0, 1};
  LocaliserFrame frame{0, -1, geometry::Pose2{}, Motion{}, &visible, 0};
  PoseEstimate est = localiser.Localise(frame, store, world, trajectory, frustum, motion);
  EXPECT_EQ(est.status, PoseStatus::kInitializing);
  trajectory.Record(0, est.pose, true);

  // Both walls on the map, seen again from 0.1 m further on: tracked from the walls alone,
  // whatever the prediction said.
  world.global[0] = LineOf(corner[0], {3, 0});
  world.global[1] = LineOf(corner[1], {0, 1});
  for (int64_t id = 0; id < 2; ++id) {
    const Vector2d shift(-0.1, 0.0);
    const Observation& c = corner[static_cast<size_t>(id)];
    store.Plane(id)->Add(Seen(1, c.edge[0] + shift, c.edge[1] + shift));
  }
  frame = {1, 0, est.pose, Motion{}, &visible, 0};
  frame.motion.predicted = geometry::Pose2{0.05, 0.02, 0.0};
  est = localiser.Localise(frame, store, world, trajectory, frustum, motion);
  EXPECT_EQ(est.status, PoseStatus::kTracking);
  EXPECT_NEAR(est.pose.x, 0.1, 1e-6);
  EXPECT_NEAR(est.pose.y, 0.0, 1e-6);
  trajectory.Record(1, est.pose, true);

  // No mapped wall in view: the motion model's pose for up to motion.max_coast iterations
  // (§II.E), then LOST.
  const std::vector<int64_t> none;
  PoseStatus last = PoseStatus::kTracking;
  int coasted = 0;
  for (int64_t k = 2; k < 2 + options.motion.max_coast + 3; ++k) {
    frame = {k, k - 1, est.pose, Motion{}, &none, 0};
    frame.motion.predicted = est.pose;
    last = localiser.Localise(frame, store, world, trajectory, frustum, motion).status;
    if (last == PoseStatus::kMotionModel) ++coasted;
  }
  EXPECT_EQ(coasted, options.motion.max_coast);
  EXPECT_EQ(last, PoseStatus::kLost);
}

}  // namespace
}  // namespace relplane::mapper
