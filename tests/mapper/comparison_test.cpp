// §II.C pairwise comparison on hand-built observation sequences, checked against the geometry
// the sequences were built from.
#include "comparison/comparison.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "group_fixtures.hpp"
#include "ideal_segmenter.hpp"
#include "localisation/pose_solver.hpp"
#include "plane_store/observation.hpp"
#include "plane_store/rltplane.hpp"
#include "relplane/common/geometry.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

struct Pair {
  RltPlane a;
  RltPlane b;
  Comparison c{0, 1};
};

// Drives along +x; wall A is seen whole; wall B's visible part is [lo(k), hi(k)].
template <class Lo, class Hi>
Pair Build(Vector2d a0, Vector2d a1, Vector2d b0, Vector2d b1, int n, Lo lo, Hi hi) {
  ComparisonOptions options;
  auto pose = [](int k) { return geometry::Pose2{0.03 * k, 0.0, 0.0}; };
  Pair p{RltPlane(0, testing::PartSeen(pose(0), a0, a1, 0, (a1 - a0).norm(), 0), 0.05, 1000),
         RltPlane(1, testing::PartSeen(pose(0), b0, b1, lo(0), hi(0), 0), 0.05, 1000)};
  for (int k = 1; k < n; ++k) {
    p.a.Add(testing::PartSeen(pose(k), a0, a1, 0, (a1 - a0).norm(), k));
    p.b.Add(testing::PartSeen(pose(k), b0, b1, lo(k), hi(k), k));
  }
  p.c.Update(p.a, p.b, n - 1, options, 5);
  return p;
}

// Independent check: B's edge j seen from A's edge i in A's frame, from world geometry.
Vector2d Expected(Vector2d a_edge, Vector2d a_dir, Vector2d b_edge) {
  const Vector2d d = b_edge - a_edge;
  return {a_dir.dot(d), Vector2d(-a_dir.y(), a_dir.x()).dot(d)};
}

// The end wall x = 6 (seen whole) and the left wall y = 1 from x = 2 to x = 9.
const Vector2d kEnd0{6, -1}, kEnd1{6, 1}, kLeft0{2, 1}, kLeft1{9, 1};

TEST(Comparison, GrowingPlaneFindsItsStaticEdge) {
  // The left wall grows: its start (x = 2) is static, its far end moves out with the view.
  Pair p = Build(
      kEnd0, kEnd1, kLeft0, kLeft1, 60, [](int) { return 0.0; },
      [](int k) { return 1.0 + 0.03 * k; });
  const Observation& oa = p.a.Latest();
  const DirectedStats& s = p.c.From(0);
  // A's edges: lo/hi along its direction; find which pairing with B's static edge was kept.
  int static_b = -1;
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      if (s.pair_count[i][j] > 0) static_b = j;
    }
  }
  ASSERT_GE(static_b, 0);
  const Observation& ob = p.b.Latest();
  // The static edge of B is the one at world x = 2: the one farther from the moving far end.
  const Vector2d world_b = geometry::Pose2{0.03 * 59, 0, 0} * ob.edge[static_b];
  EXPECT_NEAR(world_b.x(), 2.0, 1e-9);
  // Its relative location from A's edges matches the geometry.
  for (int i = 0; i < 2; ++i) {
    Vector2d mean;
    if (!s.Pair(i, static_b, &mean)) continue;
    const Vector2d a_edge = geometry::Pose2{0.03 * 59, 0, 0} * oa.edge[i];
    EXPECT_TRUE(mean.isApprox(Expected(a_edge, DirectionOf(oa.Alpha()), Vector2d(2, 1)), 1e-9));
  }
  EXPECT_NEAR(std::abs(p.c.DeltaAlpha(0)), M_PI / 2, 1e-9);
}

TEST(Comparison, ShrinkingPlaneFindsItsStaticEdge) {
  // The left wall shrinks: its far end (x = 9) is static, its near end is cut by the view.
  Pair p = Build(
      kEnd0, kEnd1, kLeft0, kLeft1, 60, [](int k) { return 1.0 + 0.03 * k; },
      [](int) { return 7.0; });
  const DirectedStats& s = p.c.From(0);
  const Observation& ob = p.b.Latest();
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      if (s.pair_count[i][j] <= 0) continue;
      const Vector2d world_b = geometry::Pose2{0.03 * 59, 0, 0} * ob.edge[j];
      EXPECT_NEAR(world_b.x(), 9.0, 1e-9) << "a dynamic edge was taken for static";
    }
  }
  EXPECT_GT(s.PairCount(0) + s.PairCount(1), 0.0);
}

TEST(Comparison, GrowingThenShrinkingSplitsTheInterval) {
  // Grows from x = 2 for 40 iterations, then shrinks towards x = 9: the static edge changes.
  auto lo = [](int k) { return k < 40 ? 0.0 : 0.05 * (k - 40); };
  auto hi = [](int k) { return k < 40 ? 1.0 + 0.1 * k : 5.0 + 0.0 * k; };
  Pair p = Build(kEnd0, kEnd1, kLeft0, kLeft1, 90, lo, hi);
  EXPECT_NE(p.b.PhaseAt(10), p.b.PhaseAt(80));
  const DirectedStats& s = p.c.From(0);
  // Both of B's edges were found static, each in its own sub-interval.
  double count_b[2] = {0, 0};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) count_b[j] += s.pair_count[i][j];
  }
  EXPECT_GT(count_b[0], 0.0);
  EXPECT_GT(count_b[1], 0.0);
}

// Hallway walls y = +1 and y = -1, both seen from their start at x = 2 (static) to the same
// place ahead, `far_rate` m further each iteration, while the sensor drives 0.03 m per iteration.
Pair AcrossTheHallway(double far_rate) {
  const Vector2d r0{2, -1}, r1{12, -1};
  ComparisonOptions options;
  Pair p{RltPlane(0, testing::PartSeen({0, 0, 0}, kLeft0, {12, 1}, 0.0, 3.0, 0), 0.05, 1000),
         RltPlane(1, testing::PartSeen({0, 0, 0}, r0, r1, 0.0, 3.0, 0), 0.05, 1000)};
  for (int k = 1; k < 60; ++k) {
    const geometry::Pose2 pose{0.03 * k, 0, 0};
    p.a.Add(testing::PartSeen(pose, kLeft0, {12, 1}, 0.0, 3.0 + far_rate * k, k));
    p.b.Add(testing::PartSeen(pose, r0, r1, 0.0, 3.0 + far_rate * k, k));
  }
  p.c.Update(p.a, p.b, 59, options, 5);
  return p;
}

TEST(Comparison, ParallelPlanesAcrossAreAmbiguous) {
  // The far ends (dynamic) move out in the view as well: the static-static and the
  // dynamic-dynamic pairings are both steady, and all four edges move in the view, so no
  // location along the walls may be taken from this comparison (§II.C).
  const Pair p = AcrossTheHallway(0.06);
  EXPECT_GT(p.c.Ambiguous(), 0);
  EXPECT_EQ(p.c.From(0).PairCount(0) + p.c.From(0).PairCount(1), 0.0);
  // The separation of the two lines is still known.
  double offset = 0.0;
  ASSERT_TRUE(p.c.From(0).Line(0, ComparisonOptions{}, &offset));
  EXPECT_NEAR(std::abs(offset), 2.0, 1e-9);
}

TEST(Comparison, ParallelPlanesAcrossWithEndsStillInTheViewAreNotAmbiguous) {
  // Both walls cut at a fixed distance ahead (the sensor's range): their far ends stand still
  // in the view while the sensor drives, so they are no wall ends, and the starts, which move
  // in the view as the sensor does, are the static pairing.
  const Pair p = AcrossTheHallway(0.03);
  EXPECT_EQ(p.c.Ambiguous(), 0);
  const DirectedStats& s = p.c.From(0);
  const geometry::Pose2 last{0.03 * 59, 0, 0};
  ASSERT_GT(s.PairCount(0) + s.PairCount(1), 0.0);
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      if (s.pair_count[i][j] <= 0) continue;
      EXPECT_NEAR((last * p.a.Latest().edge[i]).x(), 2.0, 1e-9) << "a far end taken for static";
      EXPECT_NEAR((last * p.b.Latest().edge[j]).x(), 2.0, 1e-9) << "a far end taken for static";
    }
  }
}

TEST(Comparison, AParallelLineIsKeptWhileAShortPlaneFlickersInLength) {
  // A door jamb at x = 4 (0.3 m, parallel to the end wall x = 6) reported whole and then half
  // by turns, six iterations each: every turn from growing to shrinking splits the interval
  // (§II.C), and no piece reaches the samples a static edge is judged on. The lines' distance
  // does not depend on where along the jamb its edges are, so it is still known.
  const Vector2d jamb0{4, -1.3}, jamb1{4, -1.0};
  auto hi = [](int k) { return (k / 6) % 2 == 0 ? 0.3 : 0.15; };
  Pair p = Build(
      kEnd0, kEnd1, jamb0, jamb1, 60, [](int) { return 0.0; }, hi);
  int phases = 0;
  for (int k = 1; k < 60; ++k) phases += p.b.PhaseAt(k) != p.b.PhaseAt(k - 1);
  ASSERT_GE(phases, 6) << "the jamb's length did not turn often enough to split the interval";
  for (int dir = 0; dir < 2; ++dir) {
    const DirectedStats& s = p.c.From(dir);
    int lines = 0;
    for (int i = 0; i < 2; ++i) {
      double offset = 0.0;
      if (!s.Line(i, ComparisonOptions{}, &offset)) continue;
      ++lines;
      EXPECT_NEAR(std::abs(offset), 2.0, 1e-6);
    }
    EXPECT_GT(lines, 0) << "from plane " << dir;
  }
}

// The end wall seen whole while the sensor drives along +x at `step` a frame, and a jamb's piece
// that every other `period` iterations lies 0.3 m further (a recess's back wall registered to
// it): each sub-interval is steady on its own, together they are not.
Pair EndWallAndAlternatingJamb(int period, int n, double step) {
  ComparisonOptions options;
  auto pose = [step](int k) { return geometry::Pose2{step * k, 0.0, 0.0}; };
  auto jamb = [&](int k) {
    const double x = (k / period) % 2 == 0 ? 4.0 : 4.3;
    const double len = (k / period) % 2 == 0 ? 0.3 : 0.15;
    return testing::PartSeen(pose(k), {x, -1.3}, {x, -1.0}, 0.0, len, k);
  };
  Pair p{RltPlane(0, testing::PartSeen(pose(0), kEnd0, kEnd1, 0, 2, 0), 0.05, 1000),
         RltPlane(1, jamb(0), 0.05, 1000)};
  for (int k = 1; k < n; ++k) {
    p.a.Add(testing::PartSeen(pose(k), kEnd0, kEnd1, 0, 2, k));
    p.b.Add(jamb(k));
  }
  p.c.Update(p.a, p.b, n - 1, options, 5);
  return p;
}

void ExpectNoLine(const Pair& p) {
  for (int dir = 0; dir < 2; ++dir) {
    for (int i = 0; i < 2; ++i) {
      double offset = 0.0;
      EXPECT_FALSE(p.c.From(dir).Line(i, ComparisonOptions{}, &offset))
          << "from plane " << dir << ", edge " << i << ": " << offset;
    }
  }
}

TEST(Comparison, ShortSubIntervalsThatDisagreeOnAParallelLineGiveNone) {
  // Sub-intervals of six iterations, too short to judge: the line is left unknown rather than
  // placed between the two.
  ExpectNoLine(EndWallAndAlternatingJamb(6, 60, 0.03));
}

TEST(Comparison, SubIntervalsLongEnoughToJudgeThatDisagreeOnAParallelLineGiveNone) {
  // Sub-intervals of 20 iterations, each judged on its own (min_samples 10): no one line either
  // (as for a static pairing's sub-intervals, §II.C).
  const Pair p = EndWallAndAlternatingJamb(20, 120, 0.01);
  for (int dir = 0; dir < 2; ++dir) {
    for (int i = 0; i < 2; ++i) EXPECT_GT(p.c.From(dir).line_count[i], 0.0) << "judged, " << dir;
  }
  ExpectNoLine(p);
}

TEST(Comparison, PiecesOfOneWallWhoseEndsRideWithTheViewHaveNoStaticPairing) {
  // One long wall y = 1 from x = 2, seen in two pieces while the sensor drives along it: the
  // near piece from the wall's start (static) to a split 4 m ahead of the sensor, the far
  // piece from 0.4 m beyond the split to the sensor's range 7.6 m ahead (both as the
  // segmenter leaves a wall at a grazing angle far away). The split and the range end keep
  // their distance from each other and from the sensor: steady, but no wall ends. Taken for
  // static, the near piece's split was paired with its mapped far end (a corner metres away)
  // and the pose jumped by that much.
  const Vector2d w0{2, 1}, w1{20, 1};
  ComparisonOptions options;
  auto pose = [](int k) { return geometry::Pose2{0.05 * k, 0, 0}; };
  auto near = [&](int k) { return testing::PartSeen(pose(k), w0, w1, 0.0, 0.05 * k + 2.0, k); };
  auto far = [&](int k) {
    return testing::PartSeen(pose(k), w0, w1, 0.05 * k + 2.4, 0.05 * k + 5.6, k);
  };
  RltPlane a(0, near(0), 0.05, 1000);
  RltPlane b(1, far(0), 0.05, 1000);
  for (int k = 1; k < 40; ++k) {
    a.Add(near(k));
    b.Add(far(k));
  }
  Comparison c(0, 1);
  c.Update(a, b, 39, options, 5);
  EXPECT_EQ(c.From(0).PairCount(0) + c.From(0).PairCount(1), 0.0);
  EXPECT_FALSE(a.static_now[0] || a.static_now[1]);
  EXPECT_FALSE(b.static_now[0] || b.static_now[1]);
  // Their lines still agree.
  double offset = 1.0;
  ASSERT_TRUE(c.From(0).Line(0, ComparisonOptions{}, &offset));
  EXPECT_NEAR(offset, 0.0, 1e-9);
}

TEST(Comparison, AnEdgeCutByTheViewPlacesNoLineAcrossIt) {
  // The left wall y = 1 from x = 2 is seen up to x = 5, where a jamb hides the rest (its edge
  // there cut by the view, standing still on the map), while the sensor drives towards the end
  // wall x = 6. The end wall's line, 1 m from that edge, is steady, but the edge is no wall
  // end: placed from the wall's mapped end (the corner metres on), the end wall went with it.
  ComparisonOptions options;
  auto pose = [](int k) { return geometry::Pose2{0.03 * k, 0.0, 0.0}; };
  auto left = [&](int k) {
    Observation obs = testing::PartSeen(pose(k), kLeft0, kLeft1, 0.0, 3.0, k);
    const int at_jamb = (pose(k) * obs.edge[1]).x() > (pose(k) * obs.edge[0]).x() ? 1 : 0;
    obs.cut[at_jamb] = true;
    return obs;
  };
  RltPlane a(0, left(0), 0.05, 1000);
  RltPlane b(1, testing::PartSeen(pose(0), kEnd0, kEnd1, 0, 2, 0), 0.05, 1000);
  for (int k = 1; k < 60; ++k) {
    a.Add(left(k));
    b.Add(testing::PartSeen(pose(k), kEnd0, kEnd1, 0, 2, k));
  }
  Comparison c(0, 1);
  c.Update(a, b, 59, options, 5);
  const Observation& last = a.Latest();
  const int at_jamb = last.cut[1] ? 1 : 0;
  double offset = 0.0;
  EXPECT_FALSE(c.From(0).Line(at_jamb, ComparisonOptions{}, &offset));
  // From the wall's real end (x = 2) the end wall's line is 4 m on.
  ASSERT_TRUE(c.From(0).Line(1 - at_jamb, ComparisonOptions{}, &offset));
  EXPECT_NEAR(std::abs(offset), 4.0, 1e-6);
}

TEST(Comparison, LeavingAndReenteringStartsANewSubInterval) {
  // B is out of view for 20 iterations in the middle; the comparison must not bridge the gap.
  ComparisonOptions options;
  RltPlane a(0, testing::PartSeen({0, 0, 0}, kEnd0, kEnd1, 0, 2, 0), 0.05, 1000);
  RltPlane b(1, testing::PartSeen({0, 0, 0}, kLeft0, kLeft1, 0, 1, 0), 0.05, 1000);
  for (int k = 1; k < 80; ++k) {
    const geometry::Pose2 pose{0.03 * k, 0, 0};
    a.Add(testing::PartSeen(pose, kEnd0, kEnd1, 0, 2, k));
    if (k < 30 || k >= 50) b.Add(testing::PartSeen(pose, kLeft0, kLeft1, 0, 1.0 + 0.03 * k, k));
  }
  Comparison c(0, 1);
  c.Update(a, b, 79, options, 5);
  EXPECT_DOUBLE_EQ(c.Common(), 60.0);
  EXPECT_GT(c.From(0).PairCount(0) + c.From(0).PairCount(1), 0.0);
}

TEST(Comparison, AnIterationWithAPoorFitCountsForLittleInTheOrientation) {
  // B, the left wall, is first a 0.1 m sliver at the edge of the view whose fit came out 3
  // degrees off (10 iterations), then 2 m of it is in view (10 iterations, fitted well). The
  // orientation difference weighs each iteration by both fits' orientation variance (rms over
  // the spread of the points along the wall): the sliver's iterations count for little, where
  // an unweighted average is 1.5 degrees off.
  const auto fitted = [](Observation obs, double length) {
    obs.support = static_cast<int>(1000 * length);
    obs.rms = 0.005;
    return obs;
  };
  const double off = 3.0 * M_PI / 180.0;
  const Vector2d sliver_end = kLeft0 + 0.1 * Vector2d(std::cos(off), std::sin(off));
  ComparisonOptions options;
  RltPlane a(0, fitted(testing::PartSeen({0, 0, 0}, kEnd0, kEnd1, 0, 2, 0), 2.0), 0.05, 1000);
  RltPlane b(1, fitted(testing::PartSeen({0, 0, 0}, kLeft0, sliver_end, 0, 0.1, 0), 0.1), 0.05,
             1000);
  for (int k = 1; k < 20; ++k) {
    const geometry::Pose2 pose{0.03 * k, 0, 0};
    a.Add(fitted(testing::PartSeen(pose, kEnd0, kEnd1, 0, 2, k), 2.0));
    b.Add(k < 10 ? fitted(testing::PartSeen(pose, kLeft0, sliver_end, 0, 0.1, k), 0.1)
                 : fitted(testing::PartSeen(pose, kLeft0, kLeft1, 0, 2, k), 2.0));
  }
  Comparison c(0, 1);
  c.Update(a, b, 19, options, 5);
  const double exact = b.Latest().Alpha() - a.Latest().Alpha();
  EXPECT_NEAR(geometry::WrapAngle(c.DeltaAlpha(0) - exact), 0.0, 0.002);
  EXPECT_NEAR(geometry::WrapAngle(c.DeltaAlpha(1) + exact), 0.0, 0.002);
}

TEST(RltPlane, BestOrientationWeightIsThatOfTheStoredObservations) {
  // The weight is kept as observations are added and dropped (a sliding-window maximum): it
  // must be the largest weight among those stored, not among all ever seen. The fit quality
  // goes up and down so the best one is dropped again and again.
  RltPlane plane(0, testing::PartSeen({0, 0, 0}, kEnd0, kEnd1, 0, 2, 0), 0.05, 16);  // 16 kept
  for (int k = 1; k < 200; ++k) {
    Observation obs = testing::PartSeen({0.01 * k, 0, 0}, kEnd0, kEnd1, 0, 2, k);
    obs.support = 500 + (k * 37) % 400;
    obs.rms = 0.002 + 0.001 * ((k * 13) % 7);
    plane.Add(obs);
    double best = 0.0;
    for (const Observation& o : plane.Observations())
      best = std::max(best, OrientationWeight(o, FitOptions{}));
    ASSERT_EQ(OrientationWeight(plane), best) << "iteration " << k;
  }
}

TEST(RltPlane, FullLengthKeptWhileItsRangeGrowsIsTheOneWorkedOutAfresh) {
  // Length() is not worked out again while the range seen whole only grows at its end and the
  // length came from that range's first sightings alone. Planes with the same sightings, each
  // marked whole as it comes: one asked at every iteration (kept values), others only at the
  // end (worked out once). With sightings dropped (400 kept of 700; their lengths stay in the
  // thinned sample) the kept value must follow, as the fresh one does.
  const auto sighting = [](int k) {
    const double noise = 0.004 * std::sin(0.7 * k) + 0.003 * std::cos(1.3 * k);
    return testing::PartSeen({0.01 * k, 0, 0}, kEnd0, kEnd1, 0, 2 + noise, k);
  };
  RltPlane asked(0, sighting(0), 0.05, 400), fresh(0, sighting(0), 0.05, 400);
  for (int k = 1; k < 700; ++k) {
    asked.Add(sighting(k));
    fresh.Add(sighting(k));
    asked.MarkFull(0, k);
    fresh.MarkFull(0, k);
    const double kept = asked.Length();
    if (k % 50 == 0 || k == 699) {
      RltPlane once(0, sighting(0), 0.05, 400);
      for (int q = 1; q <= k; ++q) {
        once.Add(sighting(q));
        once.MarkFull(0, q);
      }
      ASSERT_EQ(kept, once.Length()) << "iteration " << k;
    }
  }
  EXPECT_EQ(asked.Length(), fresh.Length());
}

}  // namespace
}  // namespace relplane::mapper
