// Unit tests of an rltplane's length (Fig. 1, §II.C "maximum size of a plane"): the largest
// length confirmed by its neighbours, the median once seen whole, and what bounded memory keeps
// of the sightings it drops.
#include <gtest/gtest.h>

#include "ideal_segmenter.hpp"
#include "plane_store/rltplane.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;
using testing::WallSeen;

// A wall taken for seen whole (both edges steady) that is later seen longer was not whole:
// an edge cut by the range stays put while the sensor turns in place. Its length is the whole
// sightings', not the mean with the partial ones, while those are fewer.
TEST(RltPlane, FullLengthIgnoresFewerSightingsShorterThanTheWallWasSeenLater) {
  RltPlane plane(0, *MakeObservation(WallSeen({2, -1}, {2, 1}), 0, 0.3), 0.05, 3000);
  for (int k = 1; k < 25; ++k) plane.Add(*MakeObservation(WallSeen({2, -1}, {2, 1}), k, 0.3));
  plane.MarkFull(0, 24);
  EXPECT_NEAR(plane.Length(), 2.0, 1e-9);
  for (int k = 25; k < 60; ++k) plane.Add(*MakeObservation(WallSeen({2, -1}, {2, 2}), k, 0.3));
  plane.MarkFull(25, 59);
  EXPECT_NEAR(plane.Length(), 3.0, 1e-9);
}

// Seen at a grazing angle from a few metres, a short piece takes in points past its end in many
// sightings of a run, two of three in a row at times: a 0.4 m pilaster face was seen up to
// 0.68 m long, and the mean of the sightings near the longest made it 0.63 m. Seen whole, its
// length is what most sightings show.
TEST(RltPlane, FullLengthOfAPieceSeenTooLongInARunOfSightingsIsWhatMostShow) {
  const Vector2d near_end(3, 0.95), far_end(3.4, 0.95);
  RltPlane plane(0, *MakeObservation(WallSeen(far_end, near_end), 0, 0.3), 0.05, 3000);
  // 0.6-0.68 m in 4 of every 10 sightings, twice two in a row; the others within 2 cm.
  const double extra[10] = {0.0, 0.25, 0.23, -0.01, 0.01, 0.28, 0.2, -0.02, 0.0, 0.02};
  for (int k = 1; k < 60; ++k) {
    const double e = extra[k % 10];
    plane.Add(*MakeObservation(WallSeen(far_end, near_end - Vector2d(e, 0)), k, 0.3));
  }
  plane.MarkFull(0, 59);
  EXPECT_NEAR(plane.Length(), 0.4, 0.025);
}

// Bounded memory drops a plane's old sightings, but what they showed still counts: a pilaster
// face seen whole at 0.3 m on a first lap, then on a second lap as 0.2 m in 60 sightings (the
// segmenter gave its corner to the wall beside it) and 0.3 m in 40, is 0.3 m long. From the
// second lap alone it was 0.2 m, and every group placing its far end from its near one had that
// end 0.1 m off.
TEST(RltPlane, FullLengthStillCountsTheWholeSightingsAlreadyDropped) {
  const Vector2d near_end(6, 0.95);
  auto seen = [&](double length, int64_t k) {
    return *MakeObservation(WallSeen(near_end, near_end + length * Vector2d(0, 1)), k, 0.3);
  };
  RltPlane plane(0, seen(0.3, 0), 0.05, 100);  // keeps 100 sightings
  for (int k = 1; k < 100; ++k) plane.Add(seen(0.3, k));
  plane.MarkFull(0, 99);
  for (int k = 100; k < 200; ++k) plane.Add(seen(k < 160 ? 0.2 : 0.3, k));
  ASSERT_GE(plane.Observations().front().iteration, 100);  // the first lap's are gone
  plane.MarkFull(100, 199);
  EXPECT_NEAR(plane.Length(), 0.3, 1e-6);
  // The second lap's sightings, dropped in turn, count for as many as the first lap's.
  for (int k = 200; k < 400; ++k) plane.Add(seen(0.2, k));
  plane.MarkFull(200, 399);
  EXPECT_NEAR(plane.Length(), 0.2, 1e-6);  // 260 sightings at 0.2 m against 140 at 0.3 m
}

// A wall's visible length changes smoothly as the sensor moves; one sighting longer than both
// its neighbours (a strip of floor along a door jamb's foot taken with it) is not its size, seen
// whole or not (§II.C maximum size): the jamb's length put the wall beside it 0.5 m off.
TEST(RltPlane, ALengthSeenInOneSightingAloneIsNotTheWallsSize) {
  const Vector2d foot(2, -1), top(2, -0.7);  // a 0.3 m door jamb
  RltPlane plane(0, *MakeObservation(WallSeen(foot - Vector2d(0, 0.8), top), 0, 0.3), 0.05, 3000);
  for (int k = 1; k < 40; ++k) {
    // Every tenth sighting reaches 0.3 m (once 0.8 m) farther along the floor.
    const double spike = k % 10 == 5 ? (k == 25 ? 0.8 : 0.3) : 0.0;
    plane.Add(*MakeObservation(WallSeen(foot - Vector2d(0, spike), top), k, 0.3));
    if (k >= 2) {
      EXPECT_NEAR(plane.Length(), 0.3, 1e-9) << k;
    }
  }
  plane.MarkFull(0, 39);
  EXPECT_NEAR(plane.Length(), 0.3, 1e-9);
  // A wall that grows is still followed, a sighting behind.
  RltPlane growing(1, *MakeObservation(WallSeen({3, -1}, {3, 0}), 0, 0.3), 0.05, 3000);
  for (int k = 1; k < 10; ++k) {
    growing.Add(*MakeObservation(WallSeen({3, -1}, {3, 0.05 * k}), k, 0.3));
  }
  EXPECT_NEAR(growing.Length(), 1.0 + 0.05 * 8, 1e-9);
}

}  // namespace
}  // namespace relplane::mapper
