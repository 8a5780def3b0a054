// Backtracking (§II.A end): a plane that matches no recent rltplane is compared to the global map
// before it becomes a new rltplane.
#include <gtest/gtest.h>

#include "ideal_segmenter.hpp"
#include "relplane/mapper/backtracking.hpp"
#include "relplane/mapper/relative_map.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

Observation Seen(Vector2d a, Vector2d b) { return *MakeObservation(testing::WallSeen(a, b), 0, 0.3); }

// A door recess's back wall, 1 m long from x = 5 to 6, mapped from the way out: the near jamb hid
// its first 0.3 m, so the map knows the end at x = 6 (static) and the wall up to x = 5.3 only.
class BackWall : public ::testing::Test {
 protected:
  void SetUp() override {
    const Observation out = Seen({5.3, -1.3}, {6.0, -1.3});
    state_.planes.emplace(kId, RltPlane(kId, out, 0.05, 1000));
    Placement placed;
    placed.alpha = out.Alpha();
    placed.known = Known::kPoint;
    placed.ref = out.edge[0].x() > out.edge[1].x() ? 0 : 1;  // the end at x = 6
    placed.point = out.edge[placed.ref];
    state_.global[kId] = placed;
  }
  int64_t Match(Vector2d a, Vector2d b) const {
    return MatchGlobal(Seen(a, b), geometry::Pose2{}, state_, {}, BacktrackOptions{});
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

// Once the other end is known too, the wall ends there.
TEST_F(BackWall, NorOneBeyondAnEndSeenStaticLater) {
  Placement& placed = state_.global[kId];
  placed.has_other = true;
  placed.other = {5.3, -1.3};
  EXPECT_EQ(Match({5.0, -1.3}, {5.2, -1.3}), -1);
}

}  // namespace
}  // namespace relplane::mapper
