// §II.D placing a group on the global map: through the planes it shares with groups placed
// before it, also when it re-places one of them itself because it knows more about it; and,
// where those links leave its position open, from a sighting made while the walls fixed the
// pose (§II.E: the motion model carries a position the walls do not give).
#include "relplane/mapper/global_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>

#include "ideal_segmenter.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/mapper/comparison.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

Placement Placed(double alpha, const Vector2d& point, int ref, Known known) {
  Placement p;
  p.alpha = alpha, p.point = point, p.ref = ref, p.known = known;
  return p;
}

// The edge of a wall along x that lies further along x.
int FarEnd(const Observation& obs) { return obs.edge[1].x() > obs.edge[0].x() ? 1 : 0; }

// A group whose relative map is built (not dirty): its members and their relative placements,
// the first one the basis.
Group Built(int64_t id, int64_t created, const std::map<int64_t, Placement>& relative,
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

// A wall from a to b as seen from (x, 0) facing along x, at iteration k.
Observation SeenAlongX(const Vector2d& a, const Vector2d& b, double x, int64_t k) {
  return *MakeObservation(testing::WallSeen(a - Vector2d(x, 0), b - Vector2d(x, 0)), k, 0.3);
}

// The same with its far end cut by the view when `cut`.
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
    state.poses[k] = {0.1 * static_cast<double>(k), 0.0, 0.0};
    if (k <= last_fixed) state.fixed_poses.insert(k);
  }
  return state;
}

// Plane 0 (an end wall x = 4) and the others known by their ends (`ends`): group 0 maps the end
// wall's line, group 1 (made at iteration `created`) knows it by its orientation only, so nothing
// links group 1's position and its prior places it.
void PlaceByPriorOnly(MapperState* state, const Observation& end, int64_t created,
                      const std::map<int64_t, Placement>& ends) {
  state->Plane(0)->groups = {0, 1};
  std::map<int64_t, Placement> relative = ends;
  for (const auto& [id, placed] : ends) state->Plane(id)->groups = {1};
  relative[0] = Placed(end.Alpha(), {0, 0}, -1, Known::kAngle);
  const Placement end_line = Placed(end.Alpha(), {4, 0}, -1, Known::kLine);
  state->groups = {Built(0, 0, {{0, end_line}}, 0), Built(1, created, relative, 1)};
  state->global = {{0, end_line}};
  state->placed_by = {{0, 0}};
  BuildGlobalMap(*state, 1, MapperOptions{});
}

// PlaceByPriorOnly with group 1 made at iteration `created` knowing the far ends (x = 3) of the
// hallway's two sides, `left` (y = 1) and `right` (y = -1): its prior must put both at x = 3.
void ExpectSidesPlacedAtTheirEnds(MapperState* state, RltPlane left, RltPlane right,
                                  const Observation& end, int64_t created) {
  const Placement left_end =
      Placed(left.Latest().Alpha(), {3, 1}, FarEnd(left.Latest()), Known::kPoint);
  const Placement right_end =
      Placed(right.Latest().Alpha(), {3, -1}, FarEnd(right.Latest()), Known::kPoint);
  state->planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  state->planes.emplace(1, std::move(left));
  state->planes.emplace(2, std::move(right));
  PlaceByPriorOnly(state, end, created, {{1, left_end}, {2, right_end}});
  ASSERT_TRUE(state->global.count(1) && state->global.count(2));
  EXPECT_NEAR(state->global.at(1).point.x(), 3.0, 1e-9);
  EXPECT_NEAR(state->global.at(2).point.x(), 3.0, 1e-9);
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

TEST(GlobalMap, AGroupRePlacedKeepsTheLinkItTookOverFromAnEarlierGroup) {
  // Seen from the start pose: wall A across the view (x = 2) and wall B along its left side
  // (y = 1), meeting at the corner (2, 1). Group 0 mapped A's line with the map's heading turned
  // by 0.05 rad (what the map had accumulated by then; the map must stay consistent with it).
  // Group 1 holds A and B and knows A's end at the corner, more than group 0 knew, so it placed
  // A itself. When group 1 is placed again it must still be placed through A as group 0 mapped
  // it, not from its members' first sightings as if it were the first group: B then lies at the
  // map's heading, 0.05 rad.
  const double heading = 0.05;
  const Observation a = *MakeObservation(testing::WallSeen({2, -1}, {2, 1}), 0, 0.3);
  const Observation b = *MakeObservation(testing::WallSeen({-1, 1}, {2, 1}), 0, 0.3);
  ASSERT_NEAR(a.Alpha(), -M_PI / 2, 1e-9);
  ASSERT_NEAR(b.Alpha(), 0.0, 1e-9);
  MapperState state;
  state.first_iteration = 0;
  state.poses[0] = {0.0, 0.0, 0.0};
  state.fixed_poses.insert(0);
  state.planes.emplace(0, RltPlane(0, a, 0.05, 1000));
  state.planes.emplace(1, RltPlane(1, b, 0.05, 1000));
  state.Plane(0)->groups = {0, 1};
  state.Plane(1)->groups = {1};

  Group first = Built(0, 0, {{0, Placed(-M_PI / 2, {2, 0}, -1, Known::kLine)}}, 0);
  first.placement = {0.0, 0.0, heading};
  // The frame of the start pose: A's corner end is its edge 0 (t = (0, -1)), B's its edge 1.
  Group second = Built(1, 1,
                       {{0, Placed(-M_PI / 2, {2, 1}, 0, Known::kPoint)},
                        {1, Placed(0.0, {2, 1}, 1, Known::kPoint)}},
                       0);
  second.placement = {0.0, 0.0, heading};
  state.groups = {first, second};
  // As group 1 last placed them.
  const Eigen::Rotation2Dd turn(heading);
  state.global = {{0, Placed(heading - M_PI / 2, turn * Vector2d(2, 1), 0, Known::kPoint)},
                  {1, Placed(heading, turn * Vector2d(2, 1), 1, Known::kPoint)}};
  state.placed_by = {{0, 1}, {1, 1}};

  BuildGlobalMap(state, 1, MapperOptions{});  // group 1 changed: placed again
  ASSERT_TRUE(state.global.count(1));
  EXPECT_NEAR(state.global.at(1).alpha, heading, 1e-9);
  EXPECT_NEAR(state.global.at(0).alpha, heading - M_PI / 2, 1e-9);
}

TEST(GlobalMap, AGroupKnowingItsBasisByItsLineIsPlacedFromAPoseTheWallsFixed) {
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
    state.poses[k] = {k <= 5 ? 0.0 : -0.02, 0.0, truth.yaw};
    if (k <= 5) state.fixed_poses.insert(k);
  }
  wall->groups = {1};
  side->groups = {0, 1};
  const double wall_alpha = wall->Observations().front().Alpha();
  const double side_alpha = side->Observations().front().Alpha();
  state.planes.emplace(0, std::move(*wall));
  state.planes.emplace(1, std::move(*side));
  const Group first = Built(0, 0, {{1, Placed(side_alpha, {0, -1}, -1, Known::kLine)}}, 1);
  const Group made_later = Built(1, 10,
                                 {{0, Placed(0.0, {0, 0}, -1, Known::kLine)},
                                  {1, Placed(side_alpha - wall_alpha, {0, 0}, -1, Known::kAngle)}},
                                 0);
  state.groups = {first, made_later};
  state.global = {{1, Placed(side_alpha, {0, -1}, -1, Known::kLine)}};
  state.placed_by = {{1, 0}};
  BuildGlobalMap(state, 1, MapperOptions{});
  ASSERT_TRUE(state.global.count(0));
  const Placement& placed = state.global.at(0);
  EXPECT_NEAR(std::abs(NormalOf(placed.alpha).dot(placed.point)), 3.0, 1e-6);
}

TEST(GlobalMap, APriorFromSeveralWallEndsAveragesTheirSightings) {
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
    state.poses[k] = {0.0, 0.0, 0.0};
    state.fixed_poses.insert(k);
  }
  state.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  state.planes.emplace(1, RltPlane(1, left, 0.05, 1000));
  state.planes.emplace(2, RltPlane(2, right, 0.05, 1000));
  PlaceByPriorOnly(&state, end, 6,
                   {{1, Placed(left.Alpha(), {3, 1}, FarEnd(left), Known::kPoint)},
                    {2, Placed(right.Alpha(), {3, -1}, FarEnd(right), Known::kPoint)}});
  ASSERT_TRUE(state.global.count(1) && state.global.count(2));
  EXPECT_NEAR(state.global.at(1).point.x(), 3.0, 1e-9);
  EXPECT_NEAR(state.global.at(2).point.x(), 3.0, 1e-9);
}

TEST(GlobalMap, AWallEndThatMovedSinceTheSightingBeforeDoesNotSetThePrior) {
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
    state.poses[k] = {0.1 * static_cast<double>(k), 0.0, 0.0};
    state.fixed_poses.insert(k);
  }
  RltPlane left(1, seen({-1, 1}, {3, 1}, 0.4, 4), 0.05, 1000);
  left.Add(seen({-1, 1}, {3, 1}, 0.5, 5));
  RltPlane right(2, seen({-1, -1}, {2.6, -1}, 0.4, 4), 0.05, 1000);
  right.Add(seen({-1, -1}, {2.75, -1}, 0.5, 5));
  const Observation end = seen({4, -1}, {4, 1}, 0.5, 5);
  ExpectSidesPlacedAtTheirEnds(&state, std::move(left), std::move(right), end, 6);
}

TEST(GlobalMap, AWallEndThatCreptAlongWithTheSensorDoesNotSetThePrior) {
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
    state.poses[k] = {x, 0.0, 0.0};
    state.fixed_poses.insert(k);
    if (k == 0) continue;
    left.Add(seen({-1, 1}, {3, 1}, x, k));
    right.Add(seen({-1, -1}, {2.0 + 0.045 * static_cast<double>(k), -1}, x, k));
  }
  ASSERT_FALSE(right.Latest().cut[FarEnd(right.Latest())]);
  const Observation end = seen({4, -1}, {4, 1}, 0.9, 9);
  ExpectSidesPlacedAtTheirEnds(&state, std::move(left), std::move(right), end, 10);
}

TEST(GlobalMap, AnEndSightingFarFromWhereFixedPosesSawThatEndDoesNotSetThePrior) {
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
  state.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  const Placement left_end =
      Placed(left.Latest().Alpha(), {3, 1}, FarEnd(left.Latest()), Known::kPoint);
  const Placement right_end =
      Placed(right.Latest().Alpha(), {3, -1}, FarEnd(right.Latest()), Known::kPoint);
  const Placement recess_end =
      Placed(recess.Latest().Alpha(), {3, 1.5}, FarEnd(recess.Latest()), Known::kPoint);
  state.planes.emplace(1, std::move(left));
  state.planes.emplace(2, std::move(right));
  state.planes.emplace(3, std::move(recess));
  PlaceByPriorOnly(&state, end, 10, {{1, left_end}, {2, right_end}, {3, recess_end}});
  ASSERT_TRUE(state.global.count(2) && state.global.count(3));
  EXPECT_NEAR(state.global.at(2).point.x(), 3.0, 1e-9);
  EXPECT_NEAR(state.global.at(3).point.x(), 3.0, 1e-9);
}

TEST(GlobalMap, ABasisEndThatMovedJustBeforeTheGroupWasMadeDoesNotSetThePrior) {
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
  state.planes.emplace(0, RltPlane(0, end, 0.05, 1000));
  const Placement left_end =
      Placed(left.Latest().Alpha(), {3, 1}, FarEnd(left.Latest()), Known::kPoint);
  state.planes.emplace(1, std::move(left));
  PlaceByPriorOnly(&state, end, 6, {{1, left_end}});
  ASSERT_TRUE(state.global.count(1));
  EXPECT_NEAR(state.global.at(1).point.x(), 3.0, 1e-9);
}

TEST(GlobalMap, AMemberEndThatMovedJustBeforeTheGroupWasMadeDoesNotSetThePrior) {
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

TEST(GlobalMap, AGroupWhoseEndsTheViewCutWhenItWasMadeIsPlacedFromTheEndsSeenSince) {
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

TEST(GlobalMap, AGroupMadeWhileTheMotionModelCarriedThePoseIsPlacedFromTheEndsSeenSince) {
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
    state.poses[k] = {0.3, 0.0, 0.0};
    state.fixed_poses.erase(k);
  }
  ExpectSidesSeenSincePlacedAtTheirEnds(&state, 4, 3.0, false, 5, 9, 6);
}

// Driving along x at 0.1 m an iteration, the walls fixing the pose: the end wall x = 4 (plane 0)
// seen square on, the hallway's left side y = 1 (plane 1), and its right side y = -1 (plane 2),
// which group 0 mapped by its line. Seen 2.5 m along the wall 1 m beside the sensor, the left
// side's far end (x = 3, a recess) is the last ray that met it, 4 cm short of the end
// (x = 2.96) in both sightings. Group 1, made at iteration 6, is added by the test.
MapperState HallwayWithAnEndSeenShort() {
  const auto seen = SeenAlongX;
  MapperState state = DrivingAlongX(5, 5);
  RltPlane end(0, seen({4, -1}, {4, 1}, 0.4, 4), 0.05, 1000);
  end.Add(seen({4, -1}, {4, 1}, 0.5, 5));
  RltPlane left(1, seen({-1, 1}, {2.96, 1}, 0.4, 4), 0.05, 1000);
  left.Add(seen({-1, 1}, {2.96, 1}, 0.5, 5));
  RltPlane right(2, seen({-1, -1}, {3.5, -1}, 0.4, 4), 0.05, 1000);
  right.Add(seen({-1, -1}, {3.5, -1}, 0.5, 5));
  end.groups = {1};
  left.groups = {1};
  right.groups = {0, 1};
  const Placement right_line = Placed(right.Latest().Alpha(), {0, -1}, -1, Known::kLine);
  state.planes.emplace(0, std::move(end));
  state.planes.emplace(1, std::move(left));
  state.planes.emplace(2, std::move(right));
  state.groups = {Built(0, 0, {{2, right_line}}, 2)};
  state.global = {{2, right_line}};
  state.placed_by = {{2, 0}};
  return state;
}

// The end wall and the left side's far end as HallwayWithAnEndSeenShort's group 1 placed them.
void ExpectEndWallAndLeftEndWhereTheyAre(const MapperState& state) {
  ASSERT_TRUE(state.global.count(0) && state.global.count(1));
  const Placement& placed = state.global.at(0);
  EXPECT_NEAR(std::abs(NormalOf(placed.alpha).dot(placed.point)), 4.0, 1e-6);
  EXPECT_NEAR(state.global.at(1).point.x(), 3.0, 1e-6);
  EXPECT_NEAR(state.global.at(1).point.y(), 1.0, 1e-6);
}

TEST(GlobalMap, AcrossItsBasisAGroupsPriorIsTheBasissLineNotAnEndSeenAtAGlancingAngle) {
  // Group 1's basis is the end wall, known by its line, and it knows the left side's far end;
  // the right side is its one link, so its position along x is its prior's. Across the basis
  // the prior must come from the end wall's line, not put the group 4 cm short (§II.C: an end
  // is fixed to a ray's spacing, a line by all its points; on loop_other_sensor a pilaster's
  // group was put 4 to 8 cm along the hallway).
  MapperState state = HallwayWithAnEndSeenShort();
  const auto alpha = [&](int64_t id) { return state.Plane(id)->Latest().Alpha(); };
  const Placement end_line = Placed(alpha(0), {4, 0}, -1, Known::kLine);
  const Placement left_end =
      Placed(alpha(1), {3, 1}, FarEnd(state.Plane(1)->Latest()), Known::kPoint);
  const Placement right_line = Placed(alpha(2), {0, -1}, -1, Known::kLine);
  state.groups.push_back(Built(1, 6, {{0, end_line}, {1, left_end}, {2, right_line}}, 0));
  BuildGlobalMap(state, 1, MapperOptions{});
  ExpectEndWallAndLeftEndWhereTheyAre(state);
}

TEST(GlobalMap, AGroupsPriorTakesEveryMembersLineNotOnlyTheBasiss) {
  // Group 1's basis is the left side, known by the far end seen short, and the end wall is
  // another member known by its line. The right side links group 1 by its orientation only, so
  // both directions of its position are its prior's. Along x the prior must come from the end
  // wall's line, not the left side's end (an office's last room moved 8 cm across its outer wall
  // when its basis changed from that wall to the partition beside it).
  MapperState state = HallwayWithAnEndSeenShort();
  const auto alpha = [&](int64_t id) { return state.Plane(id)->Latest().Alpha(); };
  // Group 1's frame: the left side's far end at the origin.
  const Placement left_end =
      Placed(alpha(1), {0, 0}, FarEnd(state.Plane(1)->Latest()), Known::kPoint);
  const Placement end_line = Placed(alpha(0), {1, 0}, -1, Known::kLine);
  const Placement right_angle = Placed(alpha(2), {0, -2}, -1, Known::kAngle);
  state.groups.push_back(Built(1, 6, {{0, end_line}, {1, left_end}, {2, right_angle}}, 1));
  BuildGlobalMap(state, 1, MapperOptions{});
  ExpectEndWallAndLeftEndWhereTheyAre(state);
}

TEST(GlobalMap, TheFirstGroupIsNotPlacedFromAnEndItsFirstSightingDidNotShow) {
  // From the start pose a wall across the view (x = 3) is seen whole, y from 2 to -2, across a
  // door (the lintel joins its pieces); the view cuts both edges but is not learnt yet, so they
  // are taken for ends. From x = 1 on, the piece beside the door is seen, y from 1 to 0.5, and
  // its door-side end (edge 1, at y = 0.5) is what group 0's relative map starts from. The
  // first sighting's edge 1 lies 2.5 m from that end: the group must be placed by the wall's
  // line there, and along it from the end as seen since.
  const auto seen = SeenAlongX;
  MapperState state;
  state.first_iteration = 0;
  state.poses[0] = {0.0, 0.0, 0.0};
  state.fixed_poses.insert(0);
  RltPlane wall(0, seen({3, 2}, {3, -2}, 0.0, 0), 0.05, 1000);
  ASSERT_NEAR(wall.Latest().edge[1].y(), -2.0, 1e-9);
  wall.first_seen = SeenFrom(wall.Latest(), state.poses[0]);
  for (int64_t k = 1; k <= 5; ++k) {
    wall.Add(seen({3, 1}, {3, 0.5}, 1.0, k));
    state.poses[k] = {1.0, 0.0, 0.0};
    state.fixed_poses.insert(k);
  }
  ASSERT_NEAR(wall.Latest().edge[1].y(), 0.5, 1e-9);
  wall.groups = {0};
  const double alpha = wall.first_seen.alpha;
  state.planes.emplace(0, std::move(wall));
  state.groups = {Built(0, 6, {{0, Placed(0.0, {0, 0}, 1, Known::kPoint)}}, 0)};
  BuildGlobalMap(state, 0, MapperOptions{});
  ASSERT_TRUE(state.global.count(0));
  EXPECT_NEAR(state.global.at(0).alpha, alpha, 1e-9);
  EXPECT_NEAR(state.global.at(0).point.x(), 3.0, 1e-9);
  EXPECT_NEAR(state.global.at(0).point.y(), 0.5, 1e-9);
}

TEST(GlobalMap, AWallPlacedByItsLineIsAnchoredAtThePartSeen) {
  // A door jamb (x = 3, 0.1 m of it at y = 1.5) seen from the origin, its fit 5 degrees off about
  // the middle of its points. Placed by its line from that one sighting, its point is the middle
  // of the part seen, where the line is right: the foot of the perpendicular from the sensor lies
  // 1.5 m along the jamb's line, 13 cm off the true one. The point matters wherever the line is
  // compared with another placement of the wall in a slightly different orientation (a group
  // placed through it as a link: n . (P_map - R P_group)).
  const double off = 5.0 * M_PI / 180.0;
  const Vector2d middle(3.0, 1.5), t(-std::sin(off), std::cos(off));
  const Observation jamb =
      *MakeObservation(testing::WallSeen(middle - 0.05 * t, middle + 0.05 * t), 0, 0.3);
  const geometry::Pose2 from{0.0, 0.0, 0.0};
  const Placement placed = PlacementOf(jamb, from, -1);
  EXPECT_EQ(placed.known, Known::kLine);
  EXPECT_NEAR((placed.point - middle).norm(), 0.0, 1e-9);
}

TEST(GlobalMap, AWallKnownByItsOrientationOnlyIsPlacedFromItsAgreeingSightings) {
  // Standing at the origin, the walls fixing the pose. Group 0 mapped wall A (x = 3) by its line.
  // Group 1, made at iteration 6, knows A by its line and wall B (y = 1) by its orientation only,
  // so B's line comes from its sightings. From iterations 0 to 4 B was seen over 2 m with a tight
  // fit; at iteration 5, just before the group was made, only 0.2 m of it was in view (edge-on
  // through a door), fitted 3 degrees off about its middle. B must lie as its sightings agree,
  // each weighed by how well its fit fixes its orientation, not 3 degrees off as the last one.
  const double off = 3.0 * M_PI / 180.0;
  const Vector2d middle(2.0, 1.0), t(std::cos(off), std::sin(off));
  MapperState state;
  state.first_iteration = 0;
  for (int64_t k = 0; k <= 5; ++k) {
    state.poses[k] = {0.0, 0.0, 0.0};
    state.fixed_poses.insert(k);
  }
  const auto fitted = [](Observation obs, double rms, int support) {
    obs.rms = rms, obs.support = support;
    return obs;
  };
  const Observation a = *MakeObservation(testing::WallSeen({3, -2}, {3, 2}), 5, 0.3);
  RltPlane wall(0, a, 0.05, 1000);
  const Observation long_b =
      fitted(*MakeObservation(testing::WallSeen({0, 1}, {2, 1}), 0, 0.3), 0.01, 400);
  RltPlane side(1, long_b, 0.05, 1000);
  for (int64_t k = 1; k <= 4; ++k) {
    side.Add(fitted(*MakeObservation(testing::WallSeen({0, 1}, {2, 1}), k, 0.3), 0.01, 400));
  }
  side.Add(fitted(
      *MakeObservation(testing::WallSeen(middle - 0.1 * t, middle + 0.1 * t), 5, 0.3), 0.01, 40));
  wall.groups = {0, 1};
  side.groups = {1};
  const double wall_alpha = a.Alpha(), side_alpha = long_b.Alpha();
  state.planes.emplace(0, std::move(wall));
  state.planes.emplace(1, std::move(side));
  const Placement wall_line = Placed(wall_alpha, {3, 0}, -1, Known::kLine);
  const Group first = Built(0, 0, {{0, wall_line}}, 0);
  const Group made_later = Built(1, 6,
                                 {{0, Placed(0.0, {0, 0}, -1, Known::kLine)},
                                  {1, Placed(side_alpha - wall_alpha, {0, 0}, -1, Known::kAngle)}},
                                 0);
  state.groups = {first, made_later};
  state.global = {{0, wall_line}};
  state.placed_by = {{0, 0}};
  BuildGlobalMap(state, 1, MapperOptions{});
  ASSERT_TRUE(state.global.count(1));
  const Placement& placed = state.global.at(1);
  EXPECT_EQ(placed.known, Known::kLine);
  // Within 0.1 degrees and 5 mm of y = 1 at the corner; the last sighting alone: 3 degrees.
  EXPECT_LT(std::abs(std::sin(placed.alpha - side_alpha)), 0.1 * M_PI / 180.0);
  const Vector2d corner(3.0, 1.0);
  EXPECT_NEAR(NormalOf(placed.alpha).dot(corner - placed.point), 0.0, 0.005);
}

TEST(GlobalMap, AWallSeenThroughADoorTakesItsOrientationFromThePiecesOnBothSides) {
  // Standing at the origin, the walls fixing the pose, looking through a door in the wall x = 3
  // (y from -0.5 to 0.5) at the side wall y = 2 of the room beyond. The pieces of x = 3 beside
  // the door are all of that wall in view, 0.2 m each, and their fits are off the same way
  // towards the door, mirrored: the upper one (plane 0) turned by -1.5 degrees, the lower one
  // (plane 1) by +1.5. Group 0 mapped both pieces from when they were seen whole; group 1 holds
  // the upper piece and the side wall (plane 2), which it placed 1.5 degrees off through their
  // comparison alone. The lower piece's comparison with the side wall, in a later group, reads
  // the other way
  // (§V soft linking: every comparison between mapped walls places their orientations, not only
  // those of the group that placed one of them), so the side wall lies within 0.2 degrees.
  const double off = 1.5 * M_PI / 180.0;
  const Vector2d up(std::sin(off), std::cos(off)), down(std::sin(off), -std::cos(off));
  MapperState state;
  state.first_iteration = 0;
  ComparisonOptions options;
  const int64_t last = 19;
  for (int64_t k = 0; k <= last; ++k) {
    state.poses[k] = {0.0, 0.0, 0.0};
    state.fixed_poses.insert(k);
  }
  const auto seen = [](const Vector2d& a, const Vector2d& b, int64_t k) {
    return *MakeObservation(testing::WallSeen(a, b), k, 0.3);
  };
  const Vector2d upper(3, 0.5), lower(3, -0.5), side0(4, 2), side1(9, 2);
  RltPlane upper_piece(0, seen(upper, upper + 0.2 * up, 0), 0.05, 1000);
  RltPlane lower_piece(1, seen(lower, lower + 0.2 * down, 0), 0.05, 1000);
  RltPlane side(2, seen(side0, side1, 0), 0.05, 1000);
  for (int64_t k = 1; k <= last; ++k) {
    upper_piece.Add(seen(upper, upper + 0.2 * up, k));
    lower_piece.Add(seen(lower, lower + 0.2 * down, k));
    side.Add(seen(side0, side1, k));
  }
  upper_piece.groups = {0, 1};
  lower_piece.groups = {0, 2};
  side.groups = {1, 2};
  // The true orientations, as the pieces' fits would give them seen whole.
  const double wall_alpha = seen({3, 0.5}, {3, 2}, 0).Alpha();
  const double lower_alpha = seen({3, -0.5}, {3, -2}, 0).Alpha();
  const double side_alpha = seen(side0, side1, 0).Alpha();
  state.planes.emplace(0, std::move(upper_piece));
  state.planes.emplace(1, std::move(lower_piece));
  state.planes.emplace(2, std::move(side));
  for (const auto& [a, b] : {std::pair<int64_t, int64_t>{0, 1}, {0, 2}, {1, 2}}) {
    Comparison& c = state.comparisons.emplace(KeyOf(a, b), Comparison(a, b)).first->second;
    c.Update(*state.Plane(a), *state.Plane(b), last, options, 5);
  }
  const Comparison* upper_side = state.FindComparison(0, 2);
  const Comparison* lower_side = state.FindComparison(1, 2);
  ASSERT_GT(upper_side->PieceInformation(), 0.0);
  ASSERT_GT(lower_side->PieceInformation(), 0.0);
  // The comparisons read the pieces' biases, in opposite directions.
  ASSERT_NEAR(geometry::WrapAngle(upper_side->PieceAlpha(0) - (side_alpha - wall_alpha)), off,
              0.1 * off);
  ASSERT_NEAR(geometry::WrapAngle(lower_side->PieceAlpha(1) - (side_alpha - lower_alpha)), -off,
              0.1 * off);
  const Placement upper_line = Placed(wall_alpha, {3, 1}, -1, Known::kLine);
  const Placement lower_line = Placed(lower_alpha, {3, -1}, -1, Known::kLine);
  const Group first = Built(0, 0, {{0, upper_line}, {1, lower_line}}, 0);
  const Group through_door =
      Built(1, 10,
            {{0, Placed(0.0, {0, 0}, -1, Known::kLine)},
             {2, Placed(upper_side->PieceAlpha(0), {1, 2}, -1, Known::kLine)}},
            0);
  // Group 2, made later, holds the lower piece and the side wall: their comparison.
  const Group beyond =
      Built(2, 15,
            {{1, Placed(0.0, {0, 0}, -1, Known::kLine)},
             {2, Placed(lower_side->PieceAlpha(1), {1, 2}, -1, Known::kLine)}},
            1);
  state.groups = {first, through_door, beyond};
  state.global = {{0, upper_line}, {1, lower_line}};
  state.placed_by = {{0, 0}, {1, 0}};
  BuildGlobalMap(state, 1, MapperOptions{});
  ASSERT_TRUE(state.global.count(2));
  // Through the upper piece alone: 1.5 degrees.
  EXPECT_LT(std::abs(geometry::WrapAngle(state.global.at(2).alpha - side_alpha)),
            0.2 * M_PI / 180.0);
  // The first group's walls are held.
  EXPECT_NEAR(state.global.at(0).alpha, wall_alpha, 1e-12);
  EXPECT_NEAR(state.global.at(1).alpha, lower_alpha, 1e-12);
}

}  // namespace
}  // namespace relplane::mapper
