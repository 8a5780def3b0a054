// Unit tests of the learnt view (LearnedFrustum): where the field of view and the range limit
// cut walls' edges, learnt from the edges the sensor reports (§II.C: a cut edge is never a
// static edge).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "localisation/pose_solver.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

// The field of view is where cut edges pile up; one noisy edge close by must not widen it, or
// the cut edges farther out pass for wall ends.
TEST(LearnedFrustum, FindsTheBorderWhereCutEdgesPileUpDespiteANoisyCloseEdge) {
  LearnedFrustum frustum;
  const double half = M_PI / 4.0;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> bearing(-0.7, 0.7), range(1.0, 6.0);
  for (int k = 0; k < 200; ++k) {
    // Two cut edges a frame on the border, two wall ends anywhere inside.
    const double r = range(rng);
    frustum.Observe(r * Vector2d(std::cos(half), std::sin(half)));
    frustum.Observe(r * Vector2d(std::cos(half), -std::sin(half)));
    const double b = bearing(rng);
    frustum.Observe(range(rng) * Vector2d(std::cos(b), std::sin(b)));
  }
  // A cut edge 0.5 m away displaced 4 cm outwards by noise: 4.6 degrees beyond the border.
  frustum.Observe(0.5 * Vector2d(std::cos(half + 0.08), std::sin(half + 0.08)));
  EXPECT_NEAR(frustum.Limit(), half, 0.01);
  // A cut edge 4 m away, 1 cm inside the border by noise, is still cut; a wall end well inside
  // is not.
  const double inside = half - 0.01 / 4.0;
  EXPECT_TRUE(frustum.Clipped(4.0 * Vector2d(std::cos(inside), std::sin(inside))));
  EXPECT_FALSE(frustum.Clipped(4.0 * Vector2d(std::cos(half - 0.15), std::sin(half - 0.15))));
}

// Edges cut by the range limit pile up at one distance with nothing beyond; the limit is
// learned from that, and not from a world whose walls all end inside the range.
TEST(LearnedFrustum, LearnsTheRangeLimitOnlyWhereCutEdgesPileUp) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> bearing(-0.6, 0.6), range(0.5, 5.5);
  std::normal_distribution<double> noise(0.0, 0.015);
  LearnedFrustum small_world, corridor;
  for (int k = 0; k < 500; ++k) {
    const double b = bearing(rng), r = range(rng);
    small_world.Observe(r * Vector2d(std::cos(b), std::sin(b)));
    corridor.Observe(r * Vector2d(std::cos(b), std::sin(b)));
    const double cut = 6.0 + noise(rng), cb = bearing(rng);
    corridor.Observe(cut * Vector2d(std::cos(cb), std::sin(cb)));
  }
  EXPECT_TRUE(std::isinf(small_world.RangeLimit()));
  EXPECT_NEAR(corridor.RangeLimit(), 6.0, 0.1);
  EXPECT_TRUE(corridor.Clipped({5.99, 0.0}));
  EXPECT_FALSE(corridor.Clipped({5.5, 0.0}));
  EXPECT_FALSE(small_world.Clipped({5.99, 0.0}));
}

// The pile-up counts once a bin holds `view.min_pile` edges: before that the widest bearing
// seen is the limit, so an edge well inside the border is not yet judged cut.
TEST(LearnedFrustum, APileUpCountsFromTheSetNumberOfEdges) {
  MapperOptions strict;
  strict.view.min_pile = 40;
  LearnedFrustum fewer, more(strict);
  const double half = M_PI / 4.0;
  for (int k = 0; k < 30; ++k) {  // 30 cut edges on the border, one noisy edge beyond it
    for (LearnedFrustum* f : {&fewer, &more}) {
      f->Observe(3.0 * Vector2d(std::cos(half), std::sin(half)));
    }
  }
  for (LearnedFrustum* f : {&fewer, &more}) {
    f->Observe(0.5 * Vector2d(std::cos(half + 0.2), std::sin(half + 0.2)));
  }
  EXPECT_NEAR(fewer.Limit(), half, 0.01);
  EXPECT_NEAR(more.Limit(), half + 0.2, 1e-9);
  const double inside = half - 0.02;
  EXPECT_TRUE(fewer.Clipped(3.0 * Vector2d(std::cos(inside), std::sin(inside))));
  EXPECT_FALSE(more.Clipped(3.0 * Vector2d(std::cos(inside), std::sin(inside))));
}

// A sensor turning in place sees one wall end at one distance for many frames, and that pile
// can outgrow the range's (3.92 m against 5.92-5.98 m on a 6 m sensor). The range limit is the
// farthest pile with next to nothing beyond it, not the fullest; a small world with the same
// interior pile, whose walls end inside the range, still learns none.
TEST(LearnedFrustum, TheRangeLimitIsTheFarthestPileNotTheFullest) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> bearing(-0.6, 0.6), range(0.5, 5.5);
  std::normal_distribution<double> noise(0.0, 0.015), end_noise(0.0, 0.003);
  LearnedFrustum small_world, office;
  const auto at = [](double r, double b) -> Vector2d {
    return r * Vector2d(std::cos(b), std::sin(b));
  };
  for (int k = 0; k < 500; ++k) {
    const Vector2d inside = at(range(rng), bearing(rng));
    small_world.Observe(inside);
    office.Observe(inside);
    for (int i = 0; i < 3; ++i) {
      const Vector2d end = at(3.92 + end_noise(rng), bearing(rng));
      small_world.Observe(end);
      office.Observe(end);
    }
    office.Observe(at(6.0 + noise(rng), bearing(rng)));
  }
  EXPECT_TRUE(std::isinf(small_world.RangeLimit()));
  EXPECT_NEAR(office.RangeLimit(), 6.0, 0.1);
  EXPECT_TRUE(office.Clipped({5.99, 0.0}));
  EXPECT_FALSE(office.Clipped({3.92, 0.0}));
}

// Along a hallway the range cuts both side walls at one distance, 0.3 m short of an 8 m range
// (rays grazing them): a pile with nothing beyond. Turning at its end, the range cuts walls at
// other angles, thinly spread up to 8 m: they are range cuts too, and the limit stays.
TEST(LearnedFrustum, ARangeLimitStaysWhenRangeCutsAtOtherAnglesFollow) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> bearing(-0.6, 0.6), inside(0.5, 7.0), cut(7.72, 8.0);
  LearnedFrustum frustum;
  const auto at = [](double r, double b) -> Vector2d {
    return r * Vector2d(std::cos(b), std::sin(b));
  };
  for (int k = 0; k < 300; ++k) {
    frustum.Observe(at(inside(rng), bearing(rng)));
    frustum.Observe(at(7.70, 0.16));
    frustum.Observe(at(7.70, -0.16));
  }
  const double hallway = frustum.RangeLimit();
  EXPECT_NEAR(hallway, 7.78, 0.05);
  for (int k = 0; k < 300; ++k) {
    frustum.Observe(at(inside(rng), bearing(rng)));
    frustum.Observe(at(cut(rng), bearing(rng)));
  }
  EXPECT_EQ(frustum.RangeLimit(), hallway);
  EXPECT_TRUE(frustum.Clipped({7.9, 0.0}));
}

// Rays grazing a wall sample it sparsely, so the last sample within the range lies well short
// of it (0.1-0.3 m at 6 m). An edge past which the wall reaches the range within the bearing
// margin is cut; a wall end well inside is not, nor an edge past which the wall comes nearer,
// nor any edge while no range limit is known.
TEST(LearnedFrustum, AnEdgeShortOfTheRangeOnAGrazedWallIsCut) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> bearing(-0.6, 0.6), range(0.5, 5.5);
  std::normal_distribution<double> noise(0.0, 0.015);
  LearnedFrustum frustum, unknown_range;
  for (int k = 0; k < 500; ++k) {
    // Edges cut by the view's border at +-40 degrees, wall ends inside, range-cut edges at 6 m.
    for (const double b : {-0.7, 0.7}) {
      const Vector2d border = range(rng) * Vector2d(std::cos(b), std::sin(b));
      frustum.Observe(border);
      unknown_range.Observe(border);
    }
    const double b = bearing(rng), r = range(rng), cb = bearing(rng);
    frustum.Observe(r * Vector2d(std::cos(b), std::sin(b)));
    unknown_range.Observe(r * Vector2d(std::cos(b), std::sin(b)));
    frustum.Observe((6.0 + noise(rng)) * Vector2d(std::cos(cb), std::sin(cb)));
  }
  ASSERT_NEAR(frustum.RangeLimit(), 6.0, 0.1);
  ASSERT_TRUE(std::isinf(unknown_range.RangeLimit()));
  // A side wall 1 m away along the view: seen from x = 3 to x = 5.3 (5.39 m away), where the
  // wall reaches 6 m 0.6 m further on, 1.2 degrees further round.
  const Vector2d near(3.0, 1.0), cut(5.3, 1.0), end(4.0, 1.0);
  EXPECT_FALSE(frustum.Clipped(cut));  // too far inside the range for its distance alone
  EXPECT_TRUE(frustum.Clipped(cut, near));
  EXPECT_FALSE(frustum.Clipped(end, near));
  EXPECT_FALSE(frustum.Clipped(near, cut));
  EXPECT_FALSE(unknown_range.Clipped(cut, near));
}

}  // namespace
}  // namespace relplane::mapper
