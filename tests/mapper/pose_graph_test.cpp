// Soft-linked groups (pose_graph.hpp): a loop of groups tied through shared planes is solved
// together, and a plane taken out of a group does not break the chain.
#include "global_map/pose_graph.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "ideal_segmenter.hpp"
#include "state_parts.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

// A wall as a line in a group's frame: frame angle alpha, a point on it.
Placement Line(double alpha, const Vector2d& point) {
  Placement p;
  p.alpha = alpha;
  p.point = point;
  p.known = Known::kLine;
  return p;
}

// Adds a rltplane (the observation only gives it an identity) held by `groups`; returns its id.
int64_t AddPlane(MapperState* state, const std::vector<int64_t>& groups) {
  const int64_t id = state->store.next_id++;
  PlaneInput input;
  input.normal = Eigen::Vector3d(-1, 0, 0);
  input.centroid = Eigen::Vector3d(1, 0, 0);
  input.vertices = {{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}};
  RltPlane plane(id, *MakeObservation(input, 0, 0.3), 0.05, 100);
  plane.groups = groups;
  state->store.planes.emplace(id, std::move(plane));
  for (int64_t g : groups) state->grouping.groups[g].members.push_back(id);
  return id;
}

// Adds a rltplane held by `groups` whose world line is (alpha, world_point); group k's frame is
// at (k, 0) in the world.
void AddWall(MapperState* state, const std::vector<int64_t>& groups, double alpha,
             const Vector2d& world_point) {
  const int64_t id = AddPlane(state, groups);
  for (int64_t g : groups) {
    state->grouping.groups[g].relative.members[id] =
        Line(alpha, world_point - Vector2d(static_cast<double>(g), 0.0));
  }
}

// Six groups in a row 1 m apart; consecutive ones share a cross wall (x) and a side wall (y and
// the orientation); the last shares a cross wall with the first (the loop closes). The groups
// start where hard chaining with some drift put them.
MapperState Loop() {
  MapperState state;
  for (int k = 0; k < 6; ++k) {
    Group g;
    g.id = k;
    g.placement = {1.06 * k, 0.02 * k, 0.01 * k};
    state.grouping.groups.push_back(g);
  }
  state.grouping.groups[0].placement = {0, 0, 0};
  for (int64_t k = 0; k + 1 < 6; ++k) {
    AddWall(&state, {k, k + 1}, M_PI / 2, {k + 0.5, 0.0});
    AddWall(&state, {k, k + 1}, 0.0, {k + 0.5, 1.0});
  }
  AddWall(&state, {0, 5}, M_PI / 2, {2.5, 0.0});
  return state;
}

void ExpectTruth(const MapperState& state, double tolerance) {
  for (size_t k = 0; k < state.grouping.groups.size(); ++k) {
    const geometry::Pose2& p = state.grouping.groups[k].placement;
    EXPECT_NEAR(p.x, static_cast<double>(k), tolerance) << "group " << k;
    EXPECT_NEAR(p.y, 0.0, tolerance) << "group " << k;
    EXPECT_NEAR(p.yaw, 0.0, tolerance) << "group " << k;
  }
}

// The solve run whatever the chained placements hold: the tests of how it spreads an error
// that is there to spread (ALoopTheChainAlreadyHoldsIsNotSolved tests when it runs).
MapperOptions AlwaysSolved() {
  MapperOptions options;
  options.graph.consistent = 0.0;
  return options;
}

TEST(PoseGraph, ALoopClosureIsSpreadOverTheGroups) {
  MapperState state = Loop();
  EXPECT_EQ(GroupLoopEvidence(state.store, state.grouping, 4, 3), 0);
  EXPECT_GT(GroupLoopEvidence(state.store, state.grouping, 5, 3), 0);
  const PoseGraphResult r =
      OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_LT(r.cost_after, r.cost_before);
  ExpectTruth(state, 1e-3);
}

TEST(PoseGraph, ALoopTheChainAlreadyHoldsIsNotSolved) {
  // The chain within a few millimetres and a fraction of a milliradian of the truth: every tie
  // holds within its noise, so there is no loop error to spread, and the chain is kept whether it
  // or the ties are nearer the truth. Here the ties are exact; on a map they carry their own
  // errors (a far wall's sampled ends), and on noise-free generated world 695 the first solve,
  // its worst tie well within its sigma, moved a corridor's 25 groups and the pose 1.4 cm along
  // the corridor, where they stayed.
  MapperState state = Loop();
  for (int k = 1; k < 6; ++k) {
    state.grouping.groups[k].placement = {k + 0.003 * (k % 2), -0.002, 0.0004 * (k % 3)};
  }
  std::vector<geometry::Pose2> chained;
  for (const Group& g : state.grouping.groups) chained.push_back(g.placement);
  const PoseGraphResult r =
      OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_TRUE(r.consistent);
  EXPECT_EQ(r.iterations, 0);
  for (size_t k = 0; k < chained.size(); ++k) {
    const geometry::Pose2& p = state.grouping.groups[k].placement;
    EXPECT_EQ(p.x, chained[k].x) << "group " << k;
    EXPECT_EQ(p.y, chained[k].y) << "group " << k;
    EXPECT_EQ(p.yaw, chained[k].yaw) << "group " << k;
  }
  // Moved by an earlier solve while its chain now holds every tie: back to the chain.
  state.grouping.groups[3].placement.x += 0.05;
  const PoseGraphResult again =
      OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_TRUE(again.consistent);
  EXPECT_EQ(state.grouping.groups[3].placement.x, chained[3].x);
  // Loop()'s chain, drifted 6 cm and 0.01 rad a group: a loop error, solved.
  MapperState off = Loop();
  EXPECT_FALSE(OptimiseGroupPlacements(GlobalInputs(off), off.world, MapperOptions{}, off.grouping)
                   .consistent);
  // A loop closed by backtracking is solved however well the chain holds it: its pose tie was
  // made only where the closing pose jumped (PoseGraphOptions::tie_min_jump).
  PoseTie closing;
  closing.a_group = 5;
  closing.b_group = 0;
  closing.a = {0.0, 0.0, 0.0};
  closing.b = {5.0, 0.0, 0.0};
  closing.a_basis = closing.b_basis = -1;  // frames with no basis (RelativeMap default)
  state.world.pose_ties.push_back(closing);
  EXPECT_FALSE(
      OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping)
          .consistent);
}

TEST(PoseGraph, APlaneTakenOutOfAGroupDoesNotBreakTheChain) {
  MapperState state = Loop();
  // Group 3 loses the cross wall it shared with group 2: its position along the row now comes
  // round the loop (group 0 -> 5 -> 4 -> 3), not from group 2.
  const int64_t cross = 4;  // the walls of pair (2, 3): ids 4 (cross) and 5 (side)
  state.grouping.groups[3].relative.members.erase(cross);
  state.store.planes.at(cross).groups = {2};
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  // Along the row, where no tie holds group 3 to group 2 now, the chain's measure of it (1.06 m
  // on from group 2, 2 cm sigma) weighs in with the loop: within 2 cm of the truth, where the
  // chain alone had it 18 cm off.
  ExpectTruth(state, 0.02);
  EXPECT_NEAR(state.grouping.groups[3].placement.x, 3.0, 0.02);
}

TEST(PoseGraph, AWrongTieDoesNotBendTheLoop) {
  MapperState state = Loop();
  // A plane mis-placed by 0.5 m in one group's relative map (a wrong static pairing).
  state.grouping.groups[4].relative.members.at(6).point.x() += 0.5;
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  ExpectTruth(state, 0.02);
}

// A rltplane known by its line in groups a and b: frame angles and a point on it in each.
void AddTie(MapperState* state, int64_t a, double alpha_a, const Vector2d& point_a, int64_t b,
            double alpha_b, const Vector2d& point_b) {
  const int64_t id = AddPlane(state, {a, b});
  state->grouping.groups[a].relative.members[id] = Line(alpha_a, point_a);
  state->grouping.groups[b].relative.members[id] = Line(alpha_b, point_b);
}

// `n` groups, every one placed at the world origin.
MapperState GroupsAtTheOrigin(int n) {
  MapperState state;
  for (int k = 0; k < n; ++k) {
    Group g;
    g.id = k;
    state.grouping.groups.push_back(g);
  }
  return state;
}

TEST(PoseGraph, WallsTyingGroupsFarAlongThemDoNotTurnAnotherGroup) {
  // Group 1 is tied to group 0 by one wall (y = 1): nothing but that wall turns it, and it lies
  // along it. Group 2 is tied to group 1 by three walls whose points the two groups keep 20 m
  // apart along each wall (a point on a line is anywhere on it), and the walls disagree by
  // 4 mrad. A line's normal turns with the group: without that in the Jacobian the solution
  // turned group 1 by 3.6 mrad to meet group 2 halfway.
  MapperState state = GroupsAtTheOrigin(3);
  state.grouping.groups[2].placement = {0.05, 0.05, 0.01};
  const double along = 20.0;
  AddTie(&state, 0, 0.0, {0, 1}, 1, 0.0, {0, 1});
  AddTie(&state, 1, 0.0, {0, 1}, 2, 0.0, {along, 1});
  AddTie(&state, 1, 0.0, {0, -1}, 2, 0.004, {-along, -1});
  AddTie(&state, 1, M_PI / 2, {3, 0}, 2, M_PI / 2, {3, along});
  const PoseGraphResult r =
      OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_LT(r.cost_after, r.cost_before);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, 0.0, 1e-4);
  EXPECT_NEAR(state.grouping.groups[1].placement.y, 0.0, 1e-4);
}

TEST(PoseGraph, NearlyParallelWallsDoNotPlaceAGroupAlongThem) {
  // Group 1 shares with group 0 the two side walls of a hallway (y = 1 and y = -1), fitted
  // 0.2 degrees apart, and their lines disagree by 3 mm across: nothing says where group 1 is
  // along the hallway. Through the slight angle the two lines met 0.86 m away, and the solve
  // slid group 1 there (a leg of a hallway loop slid by a door spacing, 2.8 m).
  MapperState state;
  for (int k = 0; k < 2; ++k) {
    Group g;
    g.id = k;
    g.placement = {static_cast<double>(k), 0.0, 0.0};
    state.grouping.groups.push_back(g);
  }
  const double angle = 0.2 * M_PI / 180.0;
  AddTie(&state, 0, 0.0, {0, 1}, 1, 0.0, {-1, 1});
  AddTie(&state, 0, angle, {0, -1}, 1, angle, {-1, -1 + 0.003});
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_NEAR(state.grouping.groups[1].placement.x, 1.0, 0.01);
  EXPECT_NEAR(state.grouping.groups[1].placement.y, 0.0, 0.003);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, 0.0, 1e-4);
}

TEST(PoseGraph, AnEndPlacedThroughASpreadPairingDoesNotTurnTheGroups) {
  // Two groups share the side walls of a hallway (y = 1 and y = -1), which fix their relative
  // heading, and the end of a cross wall 6 m along it. Group 1 places that end through a static
  // pairing spread 3 cm over its interval (an end seen at a grazing angle, where the sensor's
  // rays last hit it) and has it 4 cm off along the cross wall. Weighed like a well-seen end,
  // it turned group 1 by 0.26 degrees (a turn moves it 6 m away at little cost in orientation).
  MapperState state = GroupsAtTheOrigin(2);
  AddTie(&state, 0, 0.0, {0, 1}, 1, 0.0, {0, 1});
  AddTie(&state, 0, 0.0, {0, -1}, 1, 0.0, {0, -1});
  const int64_t end = AddPlane(&state, {0, 1});
  Placement seen_well = Line(M_PI / 2, {6, -1});
  seen_well.known = Known::kPoint;
  seen_well.ref = 0;
  Placement spread = seen_well;
  spread.point.y() += 0.04;
  spread.variance = 0.03 * 0.03;
  state.grouping.groups[0].relative.members[end] = seen_well;
  state.grouping.groups[1].relative.members[end] = spread;
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, 0.0, 0.1 * M_PI / 180.0);
}

TEST(PoseGraph, SolvingAgainWithNothingNewLeavesTheGroupsWhereTheyAre) {
  // Two groups share the side walls of a hallway (y = 1 and y = -1) and one end of the upper
  // one, placed in group 1 through a static pairing spread 1 m over its interval and 0.5 m off
  // along the wall: the end is group 1's only hold along the hallway, about as weak as its prior.
  // A loop closes again and again (each closing tie that learns more solves the graph anew): a
  // prior centred on where the last solve left the group counted the end again at every solve,
  // and group 1 slid along the hallway a little further each time (0.25, 0.375, ... m).
  MapperState state = GroupsAtTheOrigin(2);
  state.grouping.groups[1].loop_evidence =
      1;  // placed by a loop: no chain from group 0 (ChainPriors)
  AddTie(&state, 0, 0.0, {0, -1}, 1, 0.0, {0, -1});
  const int64_t wall = AddPlane(&state, {0, 1});
  Placement seen_well = Line(0.0, {3, 1});
  seen_well.known = Known::kPoint;
  seen_well.ref = 0;
  Placement spread = seen_well;
  spread.point.x() += 0.5;
  spread.variance = 1.0;
  state.grouping.groups[0].relative.members[wall] = seen_well;
  state.grouping.groups[1].relative.members[wall] = spread;
  OptimiseGroupPlacements(GlobalInputs(state), state.world, AlwaysSolved(), state.grouping);
  const geometry::Pose2 first = state.grouping.groups[1].placement;
  EXPECT_LT(first.x, -0.1);  // the end does pull it (the prior is weak, not a hard anchor)
  for (int solve = 0; solve < 10; ++solve)
    OptimiseGroupPlacements(GlobalInputs(state), state.world, AlwaysSolved(), state.grouping);
  EXPECT_NEAR(state.grouping.groups[1].placement.x, first.x, 1e-3);
  EXPECT_NEAR(state.grouping.groups[1].placement.y, first.y, 1e-3);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, first.yaw, 1e-4);
}

// A hallway of four groups, the chain 1 % long along it (each group's cross wall seen 1 cm
// further on), where groups 2 and 3 share only a side wall (a turn on the spot between them: the
// chain went on from the held pose). A loop closing through backtracking (PoseTie) finds group 3
// 3 cm short of where the chain has it. The error is spread over the chain, not all put where the
// ties leave a direction open, and not left in the groups before it.
TEST(PoseGraph, ALoopClosedByBacktrackingIsSpreadOverTheChain) {
  MapperState state = GroupsAtTheOrigin(4);
  for (int k = 0; k < 4; ++k) state.grouping.groups[k].placement = {1.01 * k, 0.0, 0.0};
  for (int64_t k = 0; k < 3; ++k) {
    AddTie(&state, k, 0.0, {0, 1}, k + 1, 0.0, {0, 1});  // the side wall
    if (k < 2) AddTie(&state, k, M_PI / 2, {0.5, 0}, k + 1, M_PI / 2, {0.5 - 1.01, 0});
  }
  PoseTie closing;
  closing.a_group = 3;
  closing.b_group = 0;
  closing.a = {0.0, 0.0, 0.0};             // the sensor at group 3's origin ...
  closing.b = {3.0, 0.0, 0.0};             // ... which is 3 m on from group 0's
  closing.a_basis = closing.b_basis = -1;  // frames with no basis (RelativeMap default)
  state.world.pose_ties.push_back(closing);
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  const double x1 = state.grouping.groups[1].placement.x, x2 = state.grouping.groups[2].placement.x;
  const double x3 = state.grouping.groups[3].placement.x;
  EXPECT_LT(x3, 3.02);   // most of the 3 cm taken out
  EXPECT_LT(x1, 1.009);  // the chain before the open link gives way too
  EXPECT_LT(x2, 2.018);
  EXPECT_GT(x2 - x1, 1.0);  // in order, each link stretched or squeezed by millimetres
  EXPECT_GT(x3 - x2, 0.98);
  // Without the closing pose, nothing moves.
  MapperState open = state;
  open.world.pose_ties.clear();
  for (int k = 0; k < 4; ++k) open.grouping.groups[k].placement = {1.01 * k, 0.0, 0.0};
  OptimiseGroupPlacements(GlobalInputs(open), open.world, MapperOptions{}, open.grouping);
  EXPECT_NEAR(open.grouping.groups[3].placement.x, 3.03, 1e-4);
}

// Plane `id` as the world wall a-b seen from a sensor drifting along x and swaying, over
// iterations 0-59 (the comparisons need motion, §II.C).
void AddSeenWall(MapperState* state, int64_t id, const Vector2d& a, const Vector2d& b) {
  for (int64_t k = 0; k < 60; ++k) {
    const geometry::Pose2 sensor{0.01 * k, 0.05 * std::sin(0.05 * k), 0.05 * std::sin(0.03 * k)};
    const geometry::Pose2 inv = sensor.Inverse();
    const Observation obs = *MakeObservation(testing::WallSeen(inv * a, inv * b), k, 0.3);
    auto it = state->store.planes.find(id);
    if (it == state->store.planes.end()) {
      state->store.planes.emplace(id, RltPlane(id, obs, 0.05, 100));
    } else {
      it->second.Add(obs);
    }
  }
}

// Compares every pair of the planes AddSeenWall made (§II.C, over iterations 0-59).
void CompareAll(MapperState* state) {
  state->store.next_id = static_cast<int64_t>(state->store.planes.size());
  ComparisonOptions options;
  for (int64_t a = 0; a < state->store.next_id; ++a) {
    for (int64_t b = a + 1; b < state->store.next_id; ++b) {
      state->comparisons.pairs.try_emplace(KeyOf(a, b), a, b)
          .first->second.Update(state->store.planes.at(a), state->store.planes.at(b), 59, options,
                                5);
    }
  }
}

// CompareAll, and makes each plane a member of every group.
void ShareAll(MapperState* state) {
  CompareAll(state);
  for (size_t g = 0; g < state->grouping.groups.size(); ++g) {
    for (int64_t id = 0; id < state->store.next_id; ++id) {
      state->grouping.groups[g].members.push_back(id);
      state->store.planes.at(id).groups.push_back(static_cast<int64_t>(g));
    }
  }
}

TEST(PoseGraph, AShortPiecesOrientationDoesNotTurnTheGroups) {
  // Two groups share a hallway's side walls (y = 1 and y = -1, 5 m) and a door jamb's 10 cm face
  // across the way, whose orientation the two relative maps have 0.7 degrees apart (a short
  // face's fit is degrees off, differently from one interval to the next). The walls' comparisons
  // hold their orientations to a small fraction of that, the jamb's hold it loosely: weighed as a
  // wall's, the jamb's tie turned group 1 by 0.08 degrees, and a turn moves what lies metres away.
  MapperState state = GroupsAtTheOrigin(2);
  const int64_t upper = 0, lower = 1, jamb = 2;
  AddSeenWall(&state, upper, {4, 1}, {-1, 1});
  AddSeenWall(&state, lower, {-1, -1}, {4, -1});
  AddSeenWall(&state, jamb, {3, 0.5}, {3, 0.6});
  ShareAll(&state);
  for (int64_t g = 0; g < 2; ++g) {
    state.grouping.groups[g].relative.members[upper] = Line(M_PI, {0, 1});
    state.grouping.groups[g].relative.members[lower] = Line(0.0, {0, -1});
  }
  const double jamb_alpha = -M_PI / 2;
  state.grouping.groups[0].relative.members[jamb] = Line(jamb_alpha, {3, 0.55});
  state.grouping.groups[1].relative.members[jamb] = Line(jamb_alpha + 0.012, {3, 0.55});
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, 0.0, 2e-4);
}

TEST(PoseGraph, AShortPiecesLineFarFromItsPointDoesNotMoveTheGroups) {
  // Two groups share a hallway's side walls, an end wall behind the sensor (x = -1) and a door
  // jamb's 10 cm face ahead (x = 3). Group 1 holds the jamb by its line alone, through a point
  // 5 m along it; group 0 has the jamb's orientation 1.06 degrees off, well within what its
  // comparisons hold it to. At 5 m that angle puts the two lines 9 cm apart: weighed as a wall's
  // line, that tie pulled group 1 12 mm along the hallway against the end wall's and turned it
  // by 1.1 mrad.
  MapperState state = GroupsAtTheOrigin(2);
  const int64_t upper = 0, lower = 1, end = 2, jamb = 3;
  AddSeenWall(&state, upper, {4, 1}, {-1, 1});
  AddSeenWall(&state, lower, {-1, -1}, {4, -1});
  AddSeenWall(&state, end, {-1, 1}, {-1, -1});
  AddSeenWall(&state, jamb, {3, 0.5}, {3, 0.6});
  ShareAll(&state);
  for (int64_t g = 0; g < 2; ++g) {
    state.grouping.groups[g].relative.members[upper] = Line(M_PI, {0, 1});
    state.grouping.groups[g].relative.members[lower] = Line(0.0, {0, -1});
    state.grouping.groups[g].relative.members[end] = Line(-M_PI / 2, {-1, 0});
  }
  state.grouping.groups[0].relative.members[jamb] = Line(M_PI / 2 + 0.0185, {3, 0.55});
  state.grouping.groups[1].relative.members[jamb] = Line(M_PI / 2, {3, 0.55 - 5.0});
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_NEAR(state.grouping.groups[1].placement.x, 0.0, 0.002);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, 0.0, 2e-4);
}

TEST(PoseGraph, AGroupsBasisHoldsItsFrameWhateverItsOtherMembers) {
  // Group 0 (the anchor) holds the first room's wall x = 3, its basis, and a door jamb's 10 cm
  // face; group 1 that wall and the hallway's side walls; group 2 an end wall and another jamb,
  // which alone ties it to group 1. A loop's closing pose turns group 2 by 4 mrad. The weak link
  // is the jamb's, and the turn belongs there: weighed by its one comparison with the jamb, the
  // basis's orientation in group 0 looked as loose, and group 1 took over half the turn.
  MapperState state = GroupsAtTheOrigin(3);
  const int64_t wall = 0, jamb = 1, upper = 2, lower = 3, far_jamb = 4, end = 5;
  AddSeenWall(&state, wall, {3, -2}, {3, 2});
  AddSeenWall(&state, jamb, {3.0, 0.5}, {2.9, 0.5});
  AddSeenWall(&state, upper, {4, 1}, {-1, 1});
  AddSeenWall(&state, lower, {-1, -1}, {4, -1});
  AddSeenWall(&state, far_jamb, {3.5, -0.6}, {3.5, -0.5});
  AddSeenWall(&state, end, {-1, 1}, {-1, -1});
  CompareAll(&state);
  const std::map<int64_t, Placement> lines{{wall, Line(M_PI / 2, {3, 0})},
                                           {jamb, Line(M_PI, {2.95, 0.5})},
                                           {upper, Line(M_PI, {0, 1})},
                                           {lower, Line(0.0, {0, -1})},
                                           {far_jamb, Line(M_PI / 2, {3.5, -0.55})},
                                           {end, Line(-M_PI / 2, {-1, 0})}};
  const std::vector<std::vector<int64_t>> members{
      {wall, jamb}, {upper, wall, lower, far_jamb}, {end, far_jamb}};
  for (int64_t g = 0; g < 3; ++g) {
    Group& group = state.grouping.groups[g];
    group.relative.basis = members[g].front();
    for (int64_t id : members[g]) {
      group.members.push_back(id);
      group.relative.members[id] = lines.at(id);
      state.store.planes.at(id).groups.push_back(g);
    }
  }
  PoseTie closing;
  closing.a_group = 2;
  closing.b_group = 0;
  closing.a_basis = end;
  closing.b_basis = wall;
  closing.a = {0.0, 0.0, 0.0};    // the sensor at group 2's origin ...
  closing.b = {0.0, 0.0, 0.004};  // ... turned 4 mrad from it, as group 0 has the pose
  state.world.pose_ties.push_back(closing);
  OptimiseGroupPlacements(GlobalInputs(state), state.world, MapperOptions{}, state.grouping);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, 0.0, 3e-4);
  EXPECT_GT(state.grouping.groups[2].placement.yaw, 0.003);
}

TEST(PoseGraph, AJambAsBasisIsALooseLinkAllTheSame) {
  // Groups 0 and 1 both have a door jamb's 10 cm face as their basis, and the side walls of the
  // hallway as members. The jamb's fit was 3.6 mrad further round while group 1 was made, so
  // group 1's frame is turned by that from group 0's, and its walls the other way. The walls'
  // ties say so; the jamb's cannot, each group's frame being the jamb as fitted then. Held as
  // exact, the jamb's tie kept group 1 half way to group 0's frame.
  MapperState state = GroupsAtTheOrigin(2);
  const int64_t jamb = 0, upper = 1, lower = 2;
  AddSeenWall(&state, jamb, {3, 0.5}, {3, 0.6});
  AddSeenWall(&state, upper, {4, 1}, {-1, 1});
  AddSeenWall(&state, lower, {-1, -1}, {4, -1});
  ShareAll(&state);
  const double turn = 0.0036;
  for (int64_t g = 0; g < 2; ++g) {
    const double t = g == 0 ? 0.0 : turn;
    const Eigen::Rotation2Dd r(-t);
    Group& group = state.grouping.groups[g];
    group.relative.basis = jamb;
    group.relative.members[jamb] = Line(M_PI / 2, {3, 0.55});
    group.relative.members[upper] = Line(M_PI - t, r * Vector2d(0, 1));
    group.relative.members[lower] = Line(-t, r * Vector2d(0, -1));
  }
  OptimiseGroupPlacements(GlobalInputs(state), state.world, AlwaysSolved(), state.grouping);
  EXPECT_NEAR(state.grouping.groups[1].placement.yaw, turn, 3e-4);
}

}  // namespace
}  // namespace relplane::mapper
