// Backtracking (§II.A end): a plane that matches no recent rltplane is compared to the global map
// before it becomes a new rltplane.
#include "plane_store/backtracking.hpp"

#include <gtest/gtest.h>

#include "global_map/relative_map.hpp"
#include "ideal_segmenter.hpp"
#include "state_parts.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

Observation Seen(Vector2d a, Vector2d b) {
  return *MakeObservation(testing::WallSeen(a, b), 0, 0.3);
}

// A door recess's back wall, 1 m long from x = 5 to 6, mapped from the way out: the near jamb hid
// its first 0.3 m, so the map knows the end at x = 6 (static) and the wall up to x = 5.3 only.
class BackWall : public ::testing::Test {
 protected:
  void SetUp() override {
    const Observation out = Seen({5.3, -1.3}, {6.0, -1.3});
    state_.store.planes.emplace(kId, RltPlane(kId, out, 0.05, 1000));
    Placement placed;
    placed.alpha = out.Alpha();
    placed.known = Known::kPoint;
    placed.ref = out.edge[0].x() > out.edge[1].x() ? 0 : 1;  // the end at x = 6
    placed.point = out.edge[placed.ref];
    state_.world.global[kId] = placed;
  }
  int64_t Match(Vector2d a, Vector2d b) const { return MatchWith(a, b, {}); }
  int64_t MatchWith(Vector2d a, Vector2d b, const std::vector<const Observation*>& others) const {
    return MatchGlobal(Seen(a, b), others, geometry::Pose2{}, state_.store, state_.grouping,
                       state_.world, state_.trajectory, {}, BacktrackOptions{}, FitOptions{});
  }
  static constexpr int64_t kId = 14;
  MapperState state_;
};

// On the way back the far jamb hides the other end: the piece seen, x = 5.0 to 5.2, lies beyond
// the end the map never saw static, where the wall may go on. It is the same wall.
TEST_F(BackWall, APieceBeyondAnEndNeverSeenStaticJoinsTheWall) {
  EXPECT_EQ(Match({5.0, -1.3}, {5.2, -1.3}), kId);
}

// Beyond the static end, the same gap is another wall on the same line (the next recess).
TEST_F(BackWall, APieceBeyondTheStaticEndDoesNot) {
  EXPECT_EQ(Match({6.1, -1.3}, {6.3, -1.3}), -1);
}

// One surface per mapped wall in a frame. Generated world 33: a corridor's wall and, past its
// end, the jamb of the doorway into the next room, 0.24 m in from the wall's line and parallel
// to it. Both in view, the jamb matched the wall within the distance a loop's drift needs; its
// sightings then went to the wall, the wall was mapped 5 cm off, and the next group was chained
// from it and the pose put 2.2 m back along the corridor (ATE 1.98 m). Alone, the jamb is
// within that bound of the wall (here 0.2 m in, at its static end).
TEST_F(BackWall, ASurfaceBesideTheWallIsWithinALoopsBoundWhenSeenAlone) {
  EXPECT_EQ(Match({5.9, -1.1}, {6.05, -1.1}), kId);
}

// ... but with the wall itself on its line in the same frame, the surface beside it is another.
TEST_F(BackWall, NotWhenTheWallItselfIsInTheSameFrame) {
  const Observation wall = Seen({5.4, -1.3}, {5.95, -1.3});
  EXPECT_EQ(MatchWith({5.9, -1.1}, {6.05, -1.1}, {&wall}), -1);
}

// Two pieces of the wall itself in one frame (the segmenter split it) both lie on its line.
TEST_F(BackWall, TwoPiecesOfTheWallInOneFrameBothMatchIt) {
  const Observation piece = Seen({5.4, -1.29}, {5.6, -1.29});
  EXPECT_EQ(MatchWith({5.7, -1.31}, {5.95, -1.31}, {&piece}), kId);
}

// Once the other end is known too, the wall ends there.
TEST_F(BackWall, NorOneBeyondAnEndSeenStaticLater) {
  Placement& placed = state_.world.global[kId];
  placed.has_other = true;
  placed.other = {5.3, -1.3};
  EXPECT_EQ(Match({5.0, -1.3}, {5.2, -1.3}), -1);
}

// A room's wall from x = 3 to 5 that no static edge placed, known by its line only: seen from
// the start all but its far corner, last as a sliver beside the door at x = 5 as the sensor
// walked through. The group that placed it is frozen: the loop is a long one.
class WallKnownByItsLine : public ::testing::Test {
 protected:
  void SetUp() override {
    const Observation first = Seen({3.1, -1.3}, {5.0, -1.3});
    Observation last = Seen({4.93, -1.3}, {5.0, -1.3});
    last.iteration = 80;
    RltPlane plane(kId, first, 0.05, 1000);
    plane.first_seen = SeenFrom(first, geometry::Pose2{});
    plane.Add(last);
    state_.store.planes.emplace(kId, std::move(plane));
    state_.trajectory.poses[0] = geometry::Pose2{};
    state_.trajectory.poses[80] = geometry::Pose2{};
    Placement placed;
    placed.alpha = first.Alpha();
    placed.known = Known::kLine;
    placed.point = first.edge[0];
    state_.world.global[kId] = placed;
    state_.grouping.groups.emplace_back();
    state_.grouping.groups.back().stage = GroupStage::kFrozen;
    state_.world.placed_by[kId] = 0;
  }
  int64_t Match(Vector2d a, Vector2d b) const {
    return MatchGlobal(Seen(a, b), {}, geometry::Pose2{}, state_.store, state_.grouping,
                       state_.world, state_.trajectory, {}, BacktrackOptions{}, FitOptions{});
  }
  static constexpr int64_t kId = 7;
  MapperState state_;
};

// Back at the end of the loop, its far part is seen again, 1.7 m from the sliver the map draws:
// it is the same wall, as its first sighting shows.
TEST_F(WallKnownByItsLine, ItsFarPartSeenAgainJoinsIt) {
  EXPECT_EQ(Match({3.0, -1.3}, {3.2, -1.3}), kId);
}

// A bare line reaches no further than its sightings did (and the pose's margin): 0.15-0.35 m
// past the first sighting's end is not taken, as it would be past a mapped wall's end never
// seen static.
TEST_F(WallKnownByItsLine, ButNoFurtherThanItsSightingsReached) {
  EXPECT_EQ(Match({2.75, -1.3}, {2.95, -1.3}), -1);
}

// The same line past the door, a metre beyond anything it was seen to reach, is another wall.
TEST_F(WallKnownByItsLine, TheNextWallOnItsLineDoesNot) {
  EXPECT_EQ(Match({6.0, -1.3}, {6.4, -1.3}), -1);
}

// A piece turned further from the line than a loop's heading error and its own fit's blur is
// not the wall: here 1 m long, 8 degrees off, its middle on the line.
TEST_F(WallKnownByItsLine, NorAPieceTurnedOffItsLine) {
  const double half = 0.5, tilt = 8.0 * M_PI / 180.0;
  const Vector2d mid(4.0, -1.3), along(std::cos(tilt), std::sin(tilt));
  EXPECT_EQ(Match(mid - half * along, mid + half * along), -1);
}

// Before its group is frozen the wall's sightings are still compared: a new rltplane is made.
TEST_F(WallKnownByItsLine, NorWhileItsGroupStillComparesItsSightings) {
  state_.grouping.groups.back().stage = GroupStage::kRegrouped;
  EXPECT_EQ(Match({3.0, -1.3}, {3.2, -1.3}), -1);
}

// A wall with a mapped end on the same line wins, though the sighting fits the bare line better.
TEST_F(WallKnownByItsLine, AWallWithAMappedEndComesFirst) {
  const Observation end = Seen({3.0, -1.32}, {5.0, -1.32});
  state_.store.planes.emplace(kId + 1, RltPlane(kId + 1, end, 0.05, 1000));
  Placement placed;
  placed.alpha = end.Alpha();
  placed.known = Known::kPoint;
  placed.ref = end.edge[0].x() < end.edge[1].x() ? 0 : 1;  // the end at x = 3
  placed.point = end.edge[placed.ref];
  state_.world.global[kId + 1] = placed;
  EXPECT_EQ(Match({3.0, -1.3}, {3.2, -1.3}), kId + 1);
}

// An orientation alone places nothing to compare with.
TEST_F(WallKnownByItsLine, NorAWallKnownByItsOrientationOnly) {
  state_.world.global[kId].known = Known::kAngle;
  EXPECT_EQ(Match({4.9, -1.3}, {5.0, -1.3}), -1);
}

}  // namespace
}  // namespace relplane::mapper
