// A loop closed by backtracking (§II.A end) noted at registration and made a pose tie for the
// pose graph (§II.D), on hand-built groups and walls.
#include "global_map/loop_closure.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ideal_segmenter.hpp"
#include "state_parts.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

// Two walls in view, x = 4 and y = 1 (or both y = +-1: a hallway, open along x), placed by group
// `by`; twelve groups, each placed at the origin.
struct Scene {
  MapperState state;
  std::vector<Observation> seen;
  std::vector<Sighting> chain;

  Scene(int64_t by, bool hallway) {
    const Vector2d ends[2][2] = {{{4, -1}, {4, 1}}, {{0, 1}, {4, 1}}};
    const Vector2d side[2][2] = {{{0, -1}, {4, -1}}, {{0, 1}, {4, 1}}};
    for (int k = 0; k < 2; ++k) {
      const auto& w = hallway ? side[k] : ends[k];
      seen.push_back(*MakeObservation(testing::WallSeen(w[0], w[1]), 100, 0.3));
      state.store.planes.emplace(k, RltPlane(k, seen.back(), 0.05, 100));
      state.world.placed_by[k] = by;
    }
    for (int64_t g = 0; g < 12; ++g) {
      Group group;
      group.id = g;
      state.grouping.groups.push_back(group);
    }
    for (int k = 0; k < 2; ++k) {
      Placement p;
      p.alpha = seen[k].Alpha();
      p.point = seen[k].edge[0];
      p.known = Known::kLine;
      chain.push_back({&seen[k], &state.store.planes.at(k), p});
    }
    // A straight path up to here: not turning.
    for (int64_t i = 90; i < 100; ++i) state.trajectory.Record(i, {0.01 * i, 0, 0}, true);
  }
};

const MotionModel kMotion(MotionOptions{}, 0.1);

ClosingLoop Note(const Scene& s, int64_t oldest) {
  return NoteClosing(s.chain, {1.0, 0.0, 0.0}, oldest, s.state.world, s.state.trajectory, kMotion,
                     99, s.state.trajectory.poses.at(99), MapperOptions{});
}

TEST(LoopClosure, AChainPlacedWellAfterTheReSeenGroupCloses) {
  const Scene s(10, false);
  const ClosingLoop loop = Note(s, 2);
  ASSERT_TRUE(loop.closing);
  EXPECT_EQ(loop.from, 10);
  EXPECT_EQ(loop.to, 2);
  EXPECT_FALSE(loop.open);
  EXPECT_EQ(loop.pose.x, 1.0);
}

TEST(LoopClosure, AChainFromRecentGroupsOrNoReSeenWallClosesNothing) {
  const Scene s(4, false);
  EXPECT_FALSE(Note(s, 2).closing) << "group 4 is within recent_groups of group 2";
  EXPECT_FALSE(Note(s, -1).closing);
}

TEST(LoopClosure, AHallwayLeavesTheDirectionAlongItOpen) {
  const Scene s(10, true);
  const ClosingLoop loop = Note(s, 2);
  ASSERT_TRUE(loop.closing);
  ASSERT_TRUE(loop.open);
  EXPECT_NEAR(std::abs(std::cos(loop.open_alpha)), 1.0, 1e-9) << "open along x";
}

TEST(LoopClosure, APoseTieHoldsBothGroupsToTheSamePose) {
  Scene s(10, false);
  s.state.grouping.groups[10].placement = {0.5, 0.0, 0.1};
  s.state.grouping.groups[2].placement = {-1.0, 2.0, -0.2};
  const ClosingLoop loop = Note(s, 2);
  PoseEstimate estimate;
  estimate.status = PoseStatus::kTracking;
  estimate.pose = {1.03, 0.0, 0.0};  // the re-seen walls put the sensor 3 cm further on
  ASSERT_TRUE(AddPoseTie(loop, estimate, PoseGraphOptions{}, s.state.grouping, s.state.world));
  ASSERT_EQ(s.state.world.pose_ties.size(), 1u);
  const PoseTie& tie = s.state.world.pose_ties[0];
  EXPECT_EQ(tie.a_group, 10);
  EXPECT_EQ(tie.b_group, 2);
  const geometry::Pose2 a = s.state.grouping.groups[10].placement * tie.a;
  const geometry::Pose2 b = s.state.grouping.groups[2].placement * tie.b;
  EXPECT_NEAR(a.x, 1.0, 1e-12);
  EXPECT_NEAR(b.x, 1.03, 1e-12);
  EXPECT_EQ(s.state.world.pose_ties_made, 1);
}

// A noise-free office closed its loop 0.2 mm off, and solving the graph for it moved a wall
// 1.1 cm: a loop that closes where the chain already has the sensor makes no tie.
TEST(LoopClosure, NoTieWhereTheLoopClosesWhereTheChainHasTheSensorOrNotTracking) {
  Scene s(10, false);
  const ClosingLoop loop = Note(s, 2);
  PoseEstimate estimate;
  estimate.status = PoseStatus::kTracking;
  estimate.pose = {1.001, 0.0, 0.0};  // 1 mm: nothing to spread
  EXPECT_FALSE(AddPoseTie(loop, estimate, PoseGraphOptions{}, s.state.grouping, s.state.world));
  estimate.pose = {1.03, 0.0, 0.0};
  estimate.status = PoseStatus::kMotionModel;
  EXPECT_FALSE(AddPoseTie(loop, estimate, PoseGraphOptions{}, s.state.grouping, s.state.world));
  EXPECT_TRUE(s.state.world.pose_ties.empty());
}

TEST(LoopClosure, PoseTiesAreBounded) {
  Scene s(10, false);
  const ClosingLoop loop = Note(s, 2);
  PoseGraphOptions options;
  options.max_pose_ties = 3;
  PoseEstimate estimate;
  estimate.status = PoseStatus::kTracking;
  for (int k = 0; k < 5; ++k) {
    estimate.pose = {1.03 + 0.01 * k, 0.0, 0.0};
    ASSERT_TRUE(AddPoseTie(loop, estimate, options, s.state.grouping, s.state.world));
  }
  EXPECT_EQ(s.state.world.pose_ties.size(), 3u);
  EXPECT_EQ(s.state.world.pose_ties_made, 5);
  EXPECT_NEAR((s.state.grouping.groups[2].placement * s.state.world.pose_ties.back().b).x, 1.07,
              1e-12);
}

}  // namespace
}  // namespace relplane::mapper
