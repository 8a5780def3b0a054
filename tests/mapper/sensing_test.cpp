// An iteration's planes as the mapper takes them in (§II.A): which edges are wall ends one
// sighting may place, which the comparisons may judge static (§II.C), and which the view leaves
// open.
#include "plane_store/sensing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ideal_segmenter.hpp"
#include "sampled_walls.hpp"

namespace relplane::mapper {
namespace {

// The edge of `obs` farther along x (ahead of the sensor).
int FarEdge(const Observation& obs) { return obs.edge[1].x() > obs.edge[0].x() ? 1 : 0; }

std::vector<Observation> ObserveWith(LearnedFrustum* frustum, const std::vector<PlaneInput>& in) {
  return Observe(0, in, RegistrationOptions{}, ComparisonOptions{}.static_std, frustum);
}

// Generated world 6: a side wall split by the segmenter 4 m ahead where its samples lie 16 cm
// apart; the near piece's end, taken for the wall's end 2.7 m short of its corner, placed the
// poses 2.65 m off (ATE 1.91 m; 0.027 m once such ends place nothing). An edge whose samples lie
// further apart than √12 static_std is coarser than a static end is told by: cut for placing,
// still judged by the comparisons, which pool many sightings.
TEST(Observe, AnEdgeTheSamplesDoNotResolveIsCoarse) {
  // A corridor wall 0.75 m to the left from 1 m to 4 m ahead; a wall across, 3 m ahead.
  LearnedFrustum frustum = testing::SampledFrustum();  // 6 mrad between rays
  ASSERT_GT(frustum.EdgeSpacing({4.0, 0.75}, 0.75),
            std::sqrt(12.0) * ComparisonOptions{}.static_std);
  const std::vector<Observation> seen = ObserveWith(
      &frustum,
      {testing::WallSeen({1.0, 0.75}, {4.0, 0.75}), testing::WallSeen({3.0, -0.5}, {3.0, 0.5})});
  ASSERT_EQ(seen.size(), 2u);
  const Observation& side = seen[0];
  const Observation& across = seen[1];
  const int far = FarEdge(side);
  EXPECT_TRUE(side.cut[far]) << "13 cm between samples";
  EXPECT_TRUE(side.coarse[far]);
  EXPECT_FALSE(side.ViewCut(far));
  EXPECT_FALSE(side.cut[1 - far]) << "1 m ahead: 1.3 cm";
  EXPECT_FALSE(across.cut[0]);  // 2 cm
  EXPECT_FALSE(across.cut[1]);
}

// An edge the view cuts is a view cut, however coarse its samples.
TEST(Observe, AViewCutIsNotCoarse) {
  LearnedFrustum frustum = testing::SampledFrustum();  // 45 degrees either side
  // A wall running into the view from its left border, nearly along the border's ray.
  const std::vector<Observation> seen =
      ObserveWith(&frustum, {testing::WallSeen({2.0, 2.0}, {4.0, 3.6})});
  ASSERT_EQ(seen.size(), 1u);
  const int border = 1 - FarEdge(seen[0]);
  ASSERT_GT(frustum.EdgeSpacing(seen[0].edge[border], seen[0].d),
            std::sqrt(12.0) * ComparisonOptions{}.static_std);
  EXPECT_TRUE(seen[0].ViewCut(border));
  EXPECT_FALSE(seen[0].coarse[border]);
}

// Before the sensor's angular step is learnt no edge is coarse.
TEST(Observe, NothingIsCoarseBeforeTheStepIsLearnt) {
  LearnedFrustum frustum;
  const std::vector<Observation> seen =
      ObserveWith(&frustum, {testing::WallSeen({1.0, 0.75}, {4.0, 0.75})});
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_FALSE(seen[0].cut[FarEdge(seen[0])]);
}

}  // namespace
}  // namespace relplane::mapper
