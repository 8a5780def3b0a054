// §II.D a group's prior: where the links to the map leave a group's position open, a sighting
// made while the walls fixed the pose (§II.E: the motion model carries a position the walls do
// not give), from a wall end that stood still (§II.C), and across the members' lines as seen.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "comparison/comparison.hpp"
#include "global_map/global_map.hpp"
#include "group_fixtures.hpp"
#include "ideal_segmenter.hpp"
#include "relplane/common/geometry.hpp"
#include "state_parts.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;
using testing::Built;
using testing::Placed;
using testing::SeenAlongX;

// The edge of a wall along x that lies further along x.
int FarEnd(const Observation& obs) { return obs.edge[1].x() > obs.edge[0].x() ? 1 : 0; }

// A wall seen as SeenAlongX sees it, its far end cut by the view when `cut`.
Observation SeenAlongXCut(const Vector2d& a, const Vector2d& b, double x, int64_t k, bool cut) {
  Observation obs = SeenAlongX(a, b, x, k);
  obs.cut[FarEnd(obs)] = cut;
  return obs;
}

// Driving along x at 0.1 m an iteration up to iteration `last`; the walls fix the pose up to
// iteration `last_fixed`, then the motion model carries it (truthfully here).
MapperState DrivingAlongX(int64_t last, int64_t last_fixed) {
  MapperState state;
  state.first_iteration = 0;
  for (int64_t k = 0; k <= last; ++k) {
    state.trajectory.poses[k] = {0.1 * static_cast<double>(k), 0.0, 0.0};
    if (k <= last_fixed) state.trajectory.fixed.insert(k);
  }
  return state;
}

// Plane 0 (an end wall x = 4) and the others known by their ends (`ends`): group 0 maps the end
// wall's line, group 1 (made at iteration `created`) knows it by its orientation only, so nothing
// links group 1's position and its prior places it.
// `angular_step`: rad between the sensor's rays as the mapper learnt it (0: not known).
void PlaceByPriorOnly(MapperState* state, const Observation& end, int64_t created,
                      const std::map<int64_t, Placement>& ends, double angular_step = 0.0) {
  state->store.Plane(0)->groups = {0, 1};
  std::map<int64_t, Placement> relative = ends;
  for (const auto& [id, placed] : ends) state->store.Plane(id)->groups = {1};
  relative[0] = Placed(end.Alpha(), {0, 0}, -1, Known::kAngle);
  const Placement end_line = Placed(end.Alpha(), {4, 0}, -1, Known::kLine);
  state->grouping.groups = {Built(0, 0, {{0, end_line}}, 0), Built(1, created, relative, 1)};
  state->world.global = {{0, end_line}};
  state->world.placed_by = {{0, 0}};
  BuildGlobalMap(GlobalInputs(*state, angular_step), 1, MapperOptions{}, state->grouping,
                 state->world);
}

// PlaceByPriorOnly with group 1 made at iteration `created` knowing the far ends (x = 3) of the
// hallway's two sides, `left` (y = 1) and `right` (y = -1): its prior must put both at x = 3.
void ExpectSidesPlacedAtTheirEnds(MapperState* state, RltPlane left, RltPlane right,
                                  const Observation& end, int64_t created) {
  const Placement left_end =
      Placed(left.Latest().Alpha(), {3, 1}, FarEnd(left.Latest()), Known::kPoint);
  const Placement right_end =
      Placed(right.Latest().Alpha(), {3, -1}, FarEnd(right.Latest()), Known::kPoint);
  state->store.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  state->store.planes.emplace(1, std::move(left));
  state->store.planes.emplace(2, std::move(right));
  PlaceByPriorOnly(state, end, created, {{1, left_end}, {2, right_end}});
  ASSERT_TRUE(state->world.global.count(1) && state->world.global.count(2));
  EXPECT_NEAR(state->world.global.at(1).point.x(), 3.0, 1e-9);
  EXPECT_NEAR(state->world.global.at(2).point.x(), 3.0, 1e-9);
}

// The same with the hallway's sides first seen at iteration `first`, from x = 0.1 first, their
// far ends at x = `first_end` (where the view cut them when `cut`), then from x = 0.1 k at
// iterations k = `from` to `to` (when the end wall is seen too) with their ends at x = 3.
void ExpectSidesSeenSincePlacedAtTheirEnds(MapperState* state, int64_t first, double first_end,
                                           bool cut, int64_t from, int64_t to, int64_t created) {
  const auto seen = SeenAlongXCut;
  const auto at = [](int64_t k) { return 0.1 * static_cast<double>(k); };
  RltPlane left(1, seen({-1, 1}, {first_end, 1}, at(first), first, cut), 0.05, 1000);
  RltPlane right(2, seen({-1, -1}, {first_end, -1}, at(first), first, cut), 0.05, 1000);
  for (int64_t k = from; k <= to; ++k) {
    left.Add(seen({-1, 1}, {3, 1}, at(k), k, false));
    right.Add(seen({-1, -1}, {3, -1}, at(k), k, false));
  }
  const Observation end = seen({4, -1}, {4, 1}, at(to), to, false);
  ExpectSidesPlacedAtTheirEnds(state, std::move(left), std::move(right), end, created);
}

TEST(GroupPrior, AGroupKnowingItsBasisByItsLineIsPlacedFromAPoseTheWallsFixed) {
  // Turning in place at the origin, 0.05 rad an iteration, in front of wall W (x = 3). Group 0
  // mapped the side wall S (y = -1). Until iteration 5 the walls fixed the pose; then only W's
  // line and S's orientation were in view and the motion model let the position drift 2 cm
  // across W (x = -0.02). Group 1, made at iteration 10, knows W by its line and S by its
  // orientation: its links leave its position open, so its prior decides where W goes. That
  // must come from W as seen from a pose the walls fixed, not from the drifted one.
  const Vector2d w0(3, -2), w1(3, 2), s0(-1, -1), s1(4, -1);
  const auto seen = [](const Vector2d& a, const Vector2d& b, const geometry::Pose2& pose,
                       int64_t k) {
    const geometry::Pose2 inv = pose.Inverse();
    return *MakeObservation(testing::WallSeen(inv * a, inv * b), k, 0.3);
  };
  MapperState state;
  state.first_iteration = 0;
  std::optional<RltPlane> wall, side;
  for (int64_t k = 0; k <= 10; ++k) {
    const geometry::Pose2 truth{0.0, 0.0, 0.05 * static_cast<double>(k)};
    const Observation w = seen(w0, w1, truth, k), s = seen(s0, s1, truth, k);
    if (k == 0) {
      wall.emplace(0, w, 0.05, 1000);
      side.emplace(1, s, 0.05, 1000);
    } else {
      wall->Add(w);
      side->Add(s);
    }
    state.trajectory.poses[k] = {k <= 5 ? 0.0 : -0.02, 0.0, truth.yaw};
    if (k <= 5) state.trajectory.fixed.insert(k);
  }
  wall->groups = {1};
  side->groups = {0, 1};
  const double wall_alpha = wall->Observations().front().Alpha();
  const double side_alpha = side->Observations().front().Alpha();
  state.store.planes.emplace(0, std::move(*wall));
  state.store.planes.emplace(1, std::move(*side));
  const Group first = Built(0, 0, {{1, Placed(side_alpha, {0, -1}, -1, Known::kLine)}}, 1);
  const Group made_later = Built(1, 10,
                                 {{0, Placed(0.0, {0, 0}, -1, Known::kLine)},
                                  {1, Placed(side_alpha - wall_alpha, {0, 0}, -1, Known::kAngle)}},
                                 0);
  state.grouping.groups = {first, made_later};
  state.world.global = {{1, Placed(side_alpha, {0, -1}, -1, Known::kLine)}};
  state.world.placed_by = {{1, 0}};
  BuildGlobalMap(GlobalInputs(state), 1, MapperOptions{}, state.grouping, state.world);
  ASSERT_TRUE(state.world.global.count(0));
  const Placement& placed = state.world.global.at(0);
  EXPECT_NEAR(std::abs(NormalOf(placed.alpha).dot(placed.point)), 3.0, 1e-6);
}

TEST(GroupPrior, APriorFromSeveralWallEndsAveragesTheirSightings) {
  // Standing at the origin, the walls fixing the pose: group 1 knows the ends of the hallway's
  // two sides at x = 3 (walls y = 1 and y = -1) and the end wall x = 4 by its orientation only,
  // its one link (group 0 mapped its line): its position is its prior's. The left end was seen
  // 4 cm too far, the right one 4 cm too near (edge noise at range). The prior is the mean of
  // what each end gives, not the latest sighting alone.
  const Observation left = *MakeObservation(testing::WallSeen({1, 1}, {3.04, 1}), 5, 0.3);
  const Observation right = *MakeObservation(testing::WallSeen({1, -1}, {2.96, -1}), 4, 0.3);
  const Observation end = *MakeObservation(testing::WallSeen({4, -1}, {4, 1}), 5, 0.3);
  MapperState state;
  state.first_iteration = 0;
  for (int64_t k = 0; k <= 5; ++k) {
    state.trajectory.poses[k] = {0.0, 0.0, 0.0};
    state.trajectory.fixed.insert(k);
  }
  state.store.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  state.store.planes.emplace(1, RltPlane(1, left, 0.05, 1000));
  state.store.planes.emplace(2, RltPlane(2, right, 0.05, 1000));
  PlaceByPriorOnly(&state, end, 6,
                   {{1, Placed(left.Alpha(), {3, 1}, FarEnd(left), Known::kPoint)},
                    {2, Placed(right.Alpha(), {3, -1}, FarEnd(right), Known::kPoint)}});
  ASSERT_TRUE(state.world.global.count(1) && state.world.global.count(2));
  EXPECT_NEAR(state.world.global.at(1).point.x(), 3.0, 1e-9);
  EXPECT_NEAR(state.world.global.at(2).point.x(), 3.0, 1e-9);
}

TEST(GroupPrior, AWallEndThatMovedSinceTheSightingBeforeDoesNotSetThePrior) {
  // As above, driving along x at 0.1 m an iteration, the walls fixing the pose. Group 1 knows
  // the ends of the hallway's two sides at x = 3 and the end wall x = 4 by its orientation only:
  // its position is its prior's. The left end is seen at x = 3 from both poses before the group
  // was made. The right side's far end, hidden behind something nearer the segmenter did not
  // report, is seen uncut at x = 2.6 and then x = 2.75: it moves with the sensor, so it is not
  // the wall's end (§II.C) and must not pull the group 0.25 m / 2 short.
  const auto seen = SeenAlongX;
  MapperState state;
  state.first_iteration = 0;
  for (int64_t k = 0; k <= 5; ++k) {
    state.trajectory.poses[k] = {0.1 * static_cast<double>(k), 0.0, 0.0};
    state.trajectory.fixed.insert(k);
  }
  RltPlane left(1, seen({-1, 1}, {3, 1}, 0.4, 4), 0.05, 1000);
  left.Add(seen({-1, 1}, {3, 1}, 0.5, 5));
  RltPlane right(2, seen({-1, -1}, {2.6, -1}, 0.4, 4), 0.05, 1000);
  right.Add(seen({-1, -1}, {2.75, -1}, 0.5, 5));
  const Observation end = seen({4, -1}, {4, 1}, 0.5, 5);
  ExpectSidesPlacedAtTheirEnds(&state, std::move(left), std::move(right), end, 6);
}

TEST(GroupPrior, AWallEndThatCreptAlongWithTheSensorDoesNotSetThePrior) {
  // As above, driving along x at 0.1 m an iteration, the walls fixing the pose. The right
  // side's far end is where the sensor's range ends: seen uncut at x = 2 + 0.045 k, it creeps
  // along with the sensor by less than kEndStill an iteration, so each sighting agrees with the
  // one before, but the earlier sightings put that end 0.2 m and more behind the latest: it is
  // not the wall's end (§II.C) and must not pull the group 0.6 m / 2 short.
  const auto seen = SeenAlongX;
  MapperState state;
  state.first_iteration = 0;
  RltPlane left(1, seen({-1, 1}, {3, 1}, 0.0, 0), 0.05, 1000);
  RltPlane right(2, seen({-1, -1}, {2, -1}, 0.0, 0), 0.05, 1000);
  for (int64_t k = 0; k <= 9; ++k) {
    const double x = 0.1 * static_cast<double>(k);
    state.trajectory.poses[k] = {x, 0.0, 0.0};
    state.trajectory.fixed.insert(k);
    if (k == 0) continue;
    left.Add(seen({-1, 1}, {3, 1}, x, k));
    right.Add(seen({-1, -1}, {2.0 + 0.045 * static_cast<double>(k), -1}, x, k));
  }
  ASSERT_FALSE(right.Latest().cut[FarEnd(right.Latest())]);
  const Observation end = seen({4, -1}, {4, 1}, 0.9, 9);
  ExpectSidesPlacedAtTheirEnds(&state, std::move(left), std::move(right), end, 10);
}

TEST(GroupPrior, AnEndSightingFarFromWhereFixedPosesSawThatEndDoesNotSetThePrior) {
  // Driving along x at 0.1 m an iteration; the walls fix the pose up to iteration 5, then the
  // motion model carries it (truthfully here). Group 1, made at iteration 10, knows the far
  // ends (x = 3) of the hallway's sides and of a recess wall, and the end wall x = 4 by its
  // orientation only: its position is its prior's. No end was seen uncut from a fixed pose in
  // the latest such sighting, so the prior falls back to the sightings when the group was made:
  // the left side's (the basis) is cut by the view, the right side's, at iteration 9, is a
  // segmenter outlier 0.4 m past the end that a fixed pose saw at x = 3 (§II.C: a wall end
  // stands still). The prior must come from the recess wall's end (iteration 8), not put the
  // group 0.4 m off.
  const auto seen = SeenAlongXCut;
  MapperState state = DrivingAlongX(10, 5);
  RltPlane left(1, seen({-1, 1}, {3, 1}, 0.2, 2, true), 0.05, 1000);
  left.Add(seen({-1, 1}, {3, 1}, 0.5, 5, true));
  left.Add(seen({-1, 1}, {3, 1}, 0.9, 9, true));
  RltPlane right(2, seen({-1, -1}, {3, -1}, 0.2, 2, false), 0.05, 1000);
  right.Add(seen({-1, -1}, {3, -1}, 0.5, 5, true));
  right.Add(seen({-1, -1}, {3.4, -1}, 0.9, 9, false));
  RltPlane recess(3, seen({1, 1.5}, {3, 1.5}, 0.8, 8, false), 0.05, 1000);
  const Observation end = seen({4, -1}, {4, 1}, 0.9, 9, false);
  state.store.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  const Placement left_end =
      Placed(left.Latest().Alpha(), {3, 1}, FarEnd(left.Latest()), Known::kPoint);
  const Placement right_end =
      Placed(right.Latest().Alpha(), {3, -1}, FarEnd(right.Latest()), Known::kPoint);
  const Placement recess_end =
      Placed(recess.Latest().Alpha(), {3, 1.5}, FarEnd(recess.Latest()), Known::kPoint);
  state.store.planes.emplace(1, std::move(left));
  state.store.planes.emplace(2, std::move(right));
  state.store.planes.emplace(3, std::move(recess));
  PlaceByPriorOnly(&state, end, 10, {{1, left_end}, {2, right_end}, {3, recess_end}});
  ASSERT_TRUE(state.world.global.count(2) && state.world.global.count(3));
  EXPECT_NEAR(state.world.global.at(2).point.x(), 3.0, 1e-9);
  EXPECT_NEAR(state.world.global.at(3).point.x(), 3.0, 1e-9);
}

TEST(GroupPrior, ABasisEndThatMovedJustBeforeTheGroupWasMadeDoesNotSetThePrior) {
  // Driving along x at 0.1 m an iteration, the walls fixing the pose. Group 1, made at
  // iteration 6, knows the far end (x = 3) of its basis, the hallway's left side, and the end
  // wall x = 4 by its orientation only: its position is its prior's. Seen far off at a grazing
  // angle, that end is the last sample on the wall: uncut at x = 3 from iteration 4, then
  // 0.15 m short from iteration 5 (it moved, §II.C: a wall end stands still) and 0.12 m short
  // when the group was made; from nearer, iterations 7 to 9 see it at x = 3. The sighting when
  // the group was made must not put the group 0.12 m short (a door jamb beside a hallway wall's
  // end was mapped 0.14 m along the hallway).
  const auto seen = SeenAlongXCut;
  MapperState state = DrivingAlongX(9, 9);
  RltPlane left(1, seen({-1, 1}, {3, 1}, 0.4, 4, false), 0.05, 1000);
  left.Add(seen({-1, 1}, {2.85, 1}, 0.5, 5, false));
  left.Add(seen({-1, 1}, {2.88, 1}, 0.6, 6, false));
  for (int64_t k = 7; k <= 9; ++k) {
    left.Add(seen({-1, 1}, {3, 1}, 0.1 * static_cast<double>(k), k, false));
  }
  const Observation end = seen({4, -1}, {4, 1}, 0.9, 9, false);
  state.store.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  const Placement left_end =
      Placed(left.Latest().Alpha(), {3, 1}, FarEnd(left.Latest()), Known::kPoint);
  state.store.planes.emplace(1, std::move(left));
  PlaceByPriorOnly(&state, end, 6, {{1, left_end}});
  ASSERT_TRUE(state.world.global.count(1));
  EXPECT_NEAR(state.world.global.at(1).point.x(), 3.0, 1e-9);
}

TEST(GroupPrior, AMemberEndThatMovedJustBeforeTheGroupWasMadeDoesNotSetThePrior) {
  // Driving along x at 0.1 m an iteration, the walls fixing the pose. Group 1, made at
  // iteration 6, knows the far ends (x = 3) of the hallway's two sides and the end wall x = 4 by
  // its orientation only: its position is its prior's. The view cut the basis's (left side's)
  // end up to iteration 6, so the prior falls back to another member's end as seen when the
  // group was made. The right side's end, far off at a grazing angle, is the last sample on the
  // wall: uncut at x = 3 from iteration 4, then 0.15 m short from iteration 5 (it moved, §II.C: a
  // wall end stands still) and 0.12 m short when the group was made. From iteration 7 on both
  // ends are seen at x = 3. The member's sighting when the group was made must not put the group
  // 0.12 m short, any more than the basis's would (a door jamb's group, and the hallway after it,
  // went 0.13 m along the hallway).
  const auto seen = SeenAlongXCut;
  const auto at = [](int64_t k) { return 0.1 * static_cast<double>(k); };
  MapperState state = DrivingAlongX(9, 9);
  RltPlane left(1, seen({-1, 1}, {3, 1}, at(4), 4, true), 0.05, 1000);
  RltPlane right(2, seen({-1, -1}, {3, -1}, at(4), 4, false), 0.05, 1000);
  left.Add(seen({-1, 1}, {3, 1}, at(5), 5, true));
  right.Add(seen({-1, -1}, {2.85, -1}, at(5), 5, false));
  left.Add(seen({-1, 1}, {3, 1}, at(6), 6, true));
  right.Add(seen({-1, -1}, {2.88, -1}, at(6), 6, false));
  for (int64_t k = 7; k <= 9; ++k) {
    left.Add(seen({-1, 1}, {3, 1}, at(k), k, false));
    right.Add(seen({-1, -1}, {3, -1}, at(k), k, false));
  }
  const Observation end = seen({4, -1}, {4, 1}, at(9), 9, false);
  ExpectSidesPlacedAtTheirEnds(&state, std::move(left), std::move(right), end, 6);
}

TEST(GroupPrior, AGroupWhoseEndsTheViewCutWhenItWasMadeIsPlacedFromTheEndsSeenSince) {
  // Driving along x at 0.1 m an iteration, the walls fixing the pose. Group 1, made at
  // iteration 6, knows the far ends (x = 3) of the hallway's two sides and the end wall x = 4 by
  // its orientation only: its position is its prior's. Both sides were first seen after the
  // group was made, cut by the range at x = 1.5; from iteration 10 on the fixed poses see their
  // ends. A sighting whose end the view cut says nothing along the wall: the prior must not put
  // the group 1.5 m short (a side wall first seen where a 6 m range cut it put a group and
  // every pose after it 1.56 m off).
  MapperState state = DrivingAlongX(12, 12);
  ExpectSidesSeenSincePlacedAtTheirEnds(&state, 7, 1.5, true, 10, 12, 6);
}

TEST(GroupPrior, AGroupWhoseEndsNoFixedPoseSawIsPlacedFromTheLatestSightingOfThem) {
  // As above, but the walls fix no pose after iteration 6: from iteration 10 on the sides' ends
  // are seen at x = 3 from poses the motion model (or odometry) carried (§II.E). No fixed pose saw
  // those ends and no earlier build placed them, so the latest sighting whose end the view did
  // not cut places the group: the first, cut one lies anywhere short of the end (in the hallway
  // loop with odometry, a side wall first seen where the 8 m range cut it put the first group, and
  // every pose after it, 5 m back along the hallway).
  MapperState state = DrivingAlongX(12, 6);
  ExpectSidesSeenSincePlacedAtTheirEnds(&state, 7, 1.5, true, 10, 12, 6);
}

TEST(GroupPrior, AGroupMadeWhileTheMotionModelCarriedThePoseIsPlacedFromTheEndsSeenSince) {
  // Driving along x at 0.1 m an iteration. Group 1, made at iteration 6, knows the far ends
  // (x = 3) of the hallway's two sides and the end wall x = 4 by its orientation only: its
  // position is its prior's. The sides were first seen at iteration 4, their ends in view, while
  // the motion model held the pose at x = 0.3 (§II.E: it does not solve the position) as the
  // sensor went on to 0.6; from iteration 7 on the walls fix the pose and see the ends at x = 3.
  // The sightings when the group was made put the ends 0.3 m short: the prior must come from the
  // fixed poses (turning in place at a corner, a door jamb seen then put the group after it, and
  // the hallway, 4.6 cm along).
  MapperState state = DrivingAlongX(9, 9);
  for (int64_t k = 4; k <= 6; ++k) {
    state.trajectory.poses[k] = {0.3, 0.0, 0.0};
    state.trajectory.fixed.erase(k);
  }
  ExpectSidesSeenSincePlacedAtTheirEnds(&state, 4, 3.0, false, 5, 9, 6);
}

TEST(GroupPrior, AGroupIsNotPlacedFromAnotherEndTheRltplaneShowedBeforeItWasMade) {
  // Driving along x at 0.1 m an iteration; the walls fix the pose up to iteration 3, then the
  // motion model carries it (truthfully). From the start pose the hallway's sides were seen
  // ending at x = 1.2, uncut: the end of the collinear piece before a doorway; at iterations 1-3
  // that end was hidden (cut). From iteration 8 on they are seen ending at x = 3, and group 1,
  // made at iteration 10, knows those ends. The fixed poses saw only the other end, before the
  // group was made: the prior must come from the sightings when the group was made, not put
  // the group 1.8 m short (a corridor's group, the pose and every wall after it went 1.83 m back
  // along it).
  MapperState state = DrivingAlongX(12, 3);
  const auto at = [](int64_t k) { return 0.1 * static_cast<double>(k); };
  RltPlane left(1, SeenAlongXCut({-1, 1}, {1.2, 1}, at(0), 0, false), 0.05, 1000);
  RltPlane right(2, SeenAlongXCut({-1, -1}, {1.2, -1}, at(0), 0, false), 0.05, 1000);
  for (int64_t k = 1; k <= 3; ++k) {
    left.Add(SeenAlongXCut({-1, 1}, {1.2, 1}, at(k), k, true));
    right.Add(SeenAlongXCut({-1, -1}, {1.2, -1}, at(k), k, true));
  }
  for (int64_t k = 8; k <= 12; ++k) {
    left.Add(SeenAlongXCut({-1, 1}, {3, 1}, at(k), k, false));
    right.Add(SeenAlongXCut({-1, -1}, {3, -1}, at(k), k, false));
  }
  const Observation end = SeenAlongXCut({4, -1}, {4, 1}, at(12), 12, false);
  ExpectSidesPlacedAtTheirEnds(&state, std::move(left), std::move(right), end, 10);
}

// Driving along x at 0.1 m an iteration, the walls fixing the pose: the end wall x = 4 (plane 0)
// seen square on, the hallway's left side y = 1 (plane 1), and its right side y = -1 (plane 2),
// which group 0 mapped by its line. Seen 2.5 m along the wall 1 m beside the sensor, the left
// side's far end (x = 3, a recess) is the last ray that met it, 4 cm short of the end
// (x = 2.96) in both sightings at iterations 4 and 5. The end wall is seen at iterations
// `end_seen` and the one after (4 unless given). Group 1, made at iteration 6, is added by the
// test.
MapperState HallwayWithAnEndSeenShort(int64_t end_seen = 4) {
  const auto seen = SeenAlongX;
  const auto at = [](int64_t k) { return 0.1 * static_cast<double>(k); };
  const int64_t last = std::max<int64_t>(5, end_seen + 1);
  MapperState state = DrivingAlongX(last, last);
  RltPlane end(0, seen({4, -1}, {4, 1}, at(end_seen), end_seen), 0.05, 1000);
  end.Add(seen({4, -1}, {4, 1}, at(end_seen + 1), end_seen + 1));
  RltPlane left(1, seen({-1, 1}, {2.96, 1}, 0.4, 4), 0.05, 1000);
  left.Add(seen({-1, 1}, {2.96, 1}, 0.5, 5));
  RltPlane right(2, seen({-1, -1}, {3.5, -1}, 0.4, 4), 0.05, 1000);
  right.Add(seen({-1, -1}, {3.5, -1}, 0.5, 5));
  end.groups = {1};
  left.groups = {1};
  right.groups = {0, 1};
  const Placement right_line = Placed(right.Latest().Alpha(), {0, -1}, -1, Known::kLine);
  state.store.planes.emplace(0, std::move(end));
  state.store.planes.emplace(1, std::move(left));
  state.store.planes.emplace(2, std::move(right));
  state.grouping.groups = {Built(0, 0, {{2, right_line}}, 2)};
  state.world.global = {{2, right_line}};
  state.world.placed_by = {{2, 0}};
  return state;
}

// The end wall and the left side's far end as HallwayWithAnEndSeenShort's group 1 placed them.
void ExpectEndWallAndLeftEndWhereTheyAre(const MapperState& state) {
  ASSERT_TRUE(state.world.global.count(0) && state.world.global.count(1));
  const Placement& placed = state.world.global.at(0);
  EXPECT_NEAR(std::abs(NormalOf(placed.alpha).dot(placed.point)), 4.0, 1e-6);
  EXPECT_NEAR(state.world.global.at(1).point.x(), 3.0, 1e-6);
  EXPECT_NEAR(state.world.global.at(1).point.y(), 1.0, 1e-6);
}

TEST(GroupPrior, AcrossItsBasisAGroupsPriorIsTheBasissLineNotAnEndSeenAtAGlancingAngle) {
  // Group 1's basis is the end wall, known by its line, and it knows the left side's far end;
  // the right side is its one link, so its position along x is its prior's. Across the basis
  // the prior must come from the end wall's line, not put the group 4 cm short (§II.C: an end
  // is fixed to a ray's spacing, a line by all its points; on loop_other_sensor a pilaster's
  // group was put 4 to 8 cm along the hallway).
  MapperState state = HallwayWithAnEndSeenShort();
  const auto alpha = [&](int64_t id) { return state.store.Plane(id)->Latest().Alpha(); };
  const Placement end_line = Placed(alpha(0), {4, 0}, -1, Known::kLine);
  const Placement left_end =
      Placed(alpha(1), {3, 1}, FarEnd(state.store.Plane(1)->Latest()), Known::kPoint);
  const Placement right_line = Placed(alpha(2), {0, -1}, -1, Known::kLine);
  state.grouping.groups.push_back(Built(1, 6, {{0, end_line}, {1, left_end}, {2, right_line}}, 0));
  BuildGlobalMap(GlobalInputs(state), 1, MapperOptions{}, state.grouping, state.world);
  ExpectEndWallAndLeftEndWhereTheyAre(state);
}

TEST(GroupPrior, AGroupsPriorTakesEveryMembersLineNotOnlyTheBasiss) {
  // Group 1's basis is the left side, known by the far end seen short, and the end wall is
  // another member known by its line. The right side links group 1 by its orientation only, so
  // both directions of its position are its prior's. Along x the prior must come from the end
  // wall's line, not the left side's end (an office's last room moved 8 cm across its outer wall
  // when its basis changed from that wall to the partition beside it).
  MapperState state = HallwayWithAnEndSeenShort();
  const auto alpha = [&](int64_t id) { return state.store.Plane(id)->Latest().Alpha(); };
  // Group 1's frame: the left side's far end at the origin.
  const Placement left_end =
      Placed(alpha(1), {0, 0}, FarEnd(state.store.Plane(1)->Latest()), Known::kPoint);
  const Placement end_line = Placed(alpha(0), {1, 0}, -1, Known::kLine);
  const Placement right_angle = Placed(alpha(2), {0, -2}, -1, Known::kAngle);
  state.grouping.groups.push_back(Built(1, 6, {{0, end_line}, {1, left_end}, {2, right_angle}}, 1));
  BuildGlobalMap(GlobalInputs(state), 1, MapperOptions{}, state.grouping, state.world);
  ExpectEndWallAndLeftEndWhereTheyAre(state);
}

TEST(GroupPrior, AMemberSeenOnlySinceTheGroupWasMadeFixesADirectionTheOtherLinesLeaveOpen) {
  // As above, but the end wall comes into view only after group 1 was made (iteration 6), from
  // poses the walls fixed at iterations 7 and 8 (a 6 m range reaching a hallway's end wall). The
  // group's other lines are the hallway's two sides: along x its prior would be the left side's
  // end seen 4 cm short, while the end wall's line, seen square on, fixes it (loop_other_sensor:
  // a group 5.5 cm short of its hallway's end wall).
  MapperState state = HallwayWithAnEndSeenShort(7);
  const auto alpha = [&](int64_t id) { return state.store.Plane(id)->Latest().Alpha(); };
  // Group 1's frame: the left side's far end at the origin, the end wall 1 m past it.
  const Placement left_end =
      Placed(alpha(1), {0, 0}, FarEnd(state.store.Plane(1)->Latest()), Known::kPoint);
  const Placement end_line = Placed(alpha(0), {1, 0}, -1, Known::kLine);
  const Placement right_line = Placed(alpha(2), {0, -2}, -1, Known::kLine);
  state.grouping.groups.push_back(Built(1, 6, {{0, end_line}, {1, left_end}, {2, right_line}}, 1));
  BuildGlobalMap(GlobalInputs(state), 1, MapperOptions{}, state.grouping, state.world);
  ExpectEndWallAndLeftEndWhereTheyAre(state);
}

TEST(GroupPrior, AShortPiecesLineMeasuredMetresAwayHardlyMovesThePrior) {
  // As above, with a door jamb 0.1 m long beside the end wall (x = 3.5, y from -0.6 to -0.5)
  // in group 1, known by its line (Known::kLine) as its comparisons placed it: measured where it
  // crosses y = 3 and turned 0.02 rad, a short piece's bias, so 3.55 m away, where it stands, its
  // line is 7 cm off. Along x the end wall's line must place the group: counted as
  // fully as the end wall, the jamb moved the prior 3.5 cm (an office's room and the pose went
  // 2.7 cm across it when its basis changed, and a wall there was mapped 6 cm off).
  MapperState state = HallwayWithAnEndSeenShort();
  RltPlane jamb(3, SeenAlongX({3.5, -0.6}, {3.5, -0.5}, 0.4, 4), 0.05, 1000);
  jamb.Add(SeenAlongX({3.5, -0.6}, {3.5, -0.5}, 0.5, 5));
  jamb.groups = {1};
  state.store.planes.emplace(3, std::move(jamb));
  const auto alpha = [&](int64_t id) { return state.store.Plane(id)->Latest().Alpha(); };
  // Group 1's frame: the left side's far end at the origin (the world's (3, 1)).
  const Placement left_end =
      Placed(alpha(1), {0, 0}, FarEnd(state.store.Plane(1)->Latest()), Known::kPoint);
  const Placement end_line = Placed(alpha(0), {1, 0}, -1, Known::kLine);
  const Placement right_angle = Placed(alpha(2), {0, -2}, -1, Known::kAngle);
  const Placement jamb_line = Placed(alpha(3) + 0.02, {0.5, 2}, -1, Known::kLine);
  state.grouping.groups.push_back(
      Built(1, 6, {{0, end_line}, {1, left_end}, {2, right_angle}, {3, jamb_line}}, 1));
  BuildGlobalMap(GlobalInputs(state), 1, MapperOptions{}, state.grouping, state.world);
  ASSERT_TRUE(state.world.global.count(0) && state.world.global.count(1));
  const Placement& placed = state.world.global.at(0);
  EXPECT_NEAR(std::abs(NormalOf(placed.alpha).dot(placed.point)), 4.0, 0.002);
  EXPECT_NEAR(state.world.global.at(1).point.x(), 3.0, 0.002);
}

// Driving along x at 0.1 m an iteration, the walls fixing the pose, with `step` rad between the
// sensor's rays. Group 1, made at iteration 6, knows the far ends (x = 3) of the hallway's two
// sides and the end wall x = 4 by its orientation only: its position is its prior's. Before the
// group was made the ends were seen from x = 0.4 and 0.5 at x = `early_end`, the last sample on
// each side short of its end; from iteration 20 on they are seen 1 m off at x = 3. Returns where
// the prior put the sides' ends along x.
std::pair<double, double> SidesPlacedFromEndsSeenEarlyAndLate(double step, double early_end) {
  const auto seen = SeenAlongXCut;
  MapperState state = DrivingAlongX(22, 22);
  const auto at = [](int64_t k) { return 0.1 * static_cast<double>(k); };
  RltPlane left(1, seen({-1, 1}, {early_end, 1}, at(4), 4, false), 0.05, 1000);
  RltPlane right(2, seen({-1, -1}, {early_end, -1}, at(4), 4, false), 0.05, 1000);
  left.Add(seen({-1, 1}, {early_end, 1}, at(5), 5, false));
  right.Add(seen({-1, -1}, {early_end, -1}, at(5), 5, false));
  for (int64_t k = 20; k <= 22; ++k) {
    left.Add(seen({-1, 1}, {3, 1}, at(k), k, false));
    right.Add(seen({-1, -1}, {3, -1}, at(k), k, false));
  }
  const Observation end = seen({4, -1}, {4, 1}, at(22), 22, false);
  const double left_alpha = left.Latest().Alpha(), right_alpha = right.Latest().Alpha();
  const int left_ref = FarEnd(left.Latest()), right_ref = FarEnd(right.Latest());
  state.store.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  state.store.planes.emplace(1, std::move(left));
  state.store.planes.emplace(2, std::move(right));
  PlaceByPriorOnly(&state, end, 6,
                   {{1, Placed(left_alpha, {3, 1}, left_ref, Known::kPoint)},
                    {2, Placed(right_alpha, {3, -1}, right_ref, Known::kPoint)}},
                   step);
  if (!state.world.global.count(1) || !state.world.global.count(2)) return {NAN, NAN};
  return {state.world.global.at(1).point.x(), state.world.global.at(2).point.x()};
}

TEST(GroupPrior, AWallEndSeenCoarselyWhenTheGroupWasMadeIsTakenAsSeenMoreFinelySince) {
  // 0.56 degrees between rays (160 across 90 degrees): seen from x = 0.5 the rays meet the sides
  // at 22 degrees and land 6.8 cm apart along them, and the last sample lay 7 cm short of each
  // end; from x = 2.2 they land 1.6 cm apart. The prior must come from those (a side wall's end
  // beside a door, seen 4.6 m down a hallway, put a group and the walls it placed 10 cm along).
  const auto [left, right] = SidesPlacedFromEndsSeenEarlyAndLate(M_PI / 2 / 160, 2.93);
  EXPECT_NEAR(left, 3.0, 1e-9);
  EXPECT_NEAR(right, 3.0, 1e-9);
}

TEST(GroupPrior, AWallEndSeenFinelyEnoughWhenTheGroupWasMadeKeepsThatSighting) {
  // Twice as many rays: seen from x = 0.5 the samples land 3.4 cm apart, and the ends seen 3 cm
  // short are within the noise of an end. The fixed poses since may have been fixed by this very
  // group, so their sightings are not taken: the prior stays with the one before it was made.
  const auto [left, right] = SidesPlacedFromEndsSeenEarlyAndLate(M_PI / 2 / 320, 2.97);
  EXPECT_NEAR(left, 2.97, 1e-9);
  EXPECT_NEAR(right, 2.97, 1e-9);
}

}  // namespace
}  // namespace relplane::mapper
