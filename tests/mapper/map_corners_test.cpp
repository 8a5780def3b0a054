// §II.D end, on the published map: a wall's end is drawn where it meets the crossing wall's
// line, since its last sample lies up to a ray spacing short of the corner.
#include "published_map/map_corners.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

constexpr double kRadius = 0.1;

// A mapped wall from lo to hi, 2.5 m high, in Mapper::Map's vertex order.
MappedPlane Mapped(int64_t id, const Vector2d& lo, const Vector2d& hi) {
  MappedPlane m;
  m.id = id;
  const Vector2d t = (hi - lo).normalized();
  m.normal = Eigen::Vector3d(-t.y(), t.x(), 0.0);
  m.d = -m.normal.head<2>().dot(lo);
  m.vertices = {
      {lo.x(), lo.y(), 0.0}, {hi.x(), hi.y(), 0.0}, {hi.x(), hi.y(), 2.5}, {lo.x(), lo.y(), 2.5}};
  const Vector2d mid = 0.5 * (lo + hi);
  m.centroid = Eigen::Vector3d(mid.x(), mid.y(), 1.25);
  return m;
}

Vector2d Lo(const MappedPlane& m) { return m.vertices[0].head<2>(); }
Vector2d Hi(const MappedPlane& m) { return m.vertices[1].head<2>(); }

void ExpectAt(const Vector2d& actual, const Vector2d& expected) {
  EXPECT_NEAR(actual.x(), expected.x(), 1e-9);
  EXPECT_NEAR(actual.y(), expected.y(), 1e-9);
}

TEST(MapCorners, BothWallsOfACornerSampledShortMeetAtIt) {
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.97, 0}), Mapped(2, {4, 0.03}, {4, 3})};
  EXPECT_EQ(SnapEndsToCorners(&planes, kRadius), 2);
  ExpectAt(Hi(planes[0]), {4, 0});
  ExpectAt(Lo(planes[1]), {4, 0});
  ExpectAt(Lo(planes[0]), {0, 0});  // the far ends stay
  ExpectAt(Hi(planes[1]), {4, 3});
  // Both vertices at the end move, and the centroid with them; the line does not.
  EXPECT_NEAR(planes[0].vertices[2].x(), 4.0, 1e-9);
  EXPECT_NEAR(planes[0].vertices[2].z(), 2.5, 1e-9);
  EXPECT_NEAR(planes[0].centroid.x(), 2.0, 1e-9);
  EXPECT_NEAR(planes[0].centroid.z(), 1.25, 1e-9);
}

TEST(MapCorners, AWallEndingAtAnotherWallsFaceMeetsItAndTheOtherStays) {
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {1.96, 0}), Mapped(2, {2, -3}, {2, 3})};
  EXPECT_EQ(SnapEndsToCorners(&planes, kRadius), 1);
  ExpectAt(Hi(planes[0]), {2, 0});
  ExpectAt(Lo(planes[1]), {2, -3});
  ExpectAt(Hi(planes[1]), {2, 3});
}

TEST(MapCorners, ALongWallReachingPastTheCornerIsCutBackToIt) {
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {4.03, 0}), Mapped(2, {4, 0}, {4, 3})};
  SnapEndsToCorners(&planes, kRadius);
  ExpectAt(Hi(planes[0]), {4, 0});
}

TEST(MapCorners, TheCornerIsWhereTheLinesCrossNotWhereTheEndIs) {
  // The crossing wall at 60 degrees: the end moves along its own line to the crossing.
  const Vector2d dir(0.5, std::sqrt(3.0) / 2.0);
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.95, 0}),
                                     Mapped(2, Vector2d(4, 0) + 0.05 * dir, Vector2d(4, 0) + dir)};
  SnapEndsToCorners(&planes, kRadius);
  ExpectAt(Hi(planes[0]), {4, 0});
  ExpectAt(Lo(planes[1]), {4, 0});
}

TEST(MapCorners, EndsFartherThanTheRadiusFromAnyLineStay) {
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.85, 0}), Mapped(2, {4, 0.15}, {4, 3})};
  EXPECT_EQ(SnapEndsToCorners(&planes, kRadius), 0);
  ExpectAt(Hi(planes[0]), {3.85, 0});
  ExpectAt(Lo(planes[1]), {4, 0.15});
}

TEST(MapCorners, AWallThatDoesNotReachTheMeetingPointMakesNoCorner) {
  // The crossing line passes 3 cm from the end, but its wall starts 1 m away: a doorway.
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.97, 0}), Mapped(2, {4, 1}, {4, 3})};
  EXPECT_EQ(SnapEndsToCorners(&planes, kRadius), 0);
  ExpectAt(Hi(planes[0]), {3.97, 0});
}

TEST(MapCorners, NearParallelWallsMakeNoCorner) {
  // 20 degrees apart: where their lines cross moves far with a small error in either.
  const double a = 20.0 * M_PI / 180.0;
  const Vector2d dir(std::cos(a), std::sin(a));
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.97, 0}),
                                     Mapped(2, Vector2d(4, 0), Vector2d(4, 0) + 2.0 * dir)};
  EXPECT_EQ(SnapEndsToCorners(&planes, kRadius), 0);
}

TEST(MapCorners, AShortPieceIsLengthenedToACornerButNeverCutBack) {
  // A 15 cm jamb piece 3 cm short of a wall's line is lengthened; one reaching 3 cm past
  // another line is not cut: on a piece that short the line may be another surface's.
  std::vector<MappedPlane> planes = {Mapped(1, {1, 0.03}, {1, 0.18}), Mapped(2, {0, 0}, {3, 0}),
                                     Mapped(3, {5, -0.03}, {5, 0.12}), Mapped(4, {4, 0}, {6, 0})};
  SnapEndsToCorners(&planes, kRadius);
  ExpectAt(Lo(planes[0]), {1, 0});
  ExpectAt(Lo(planes[2]), {5, -0.03});
}

TEST(MapCorners, AShortPieceIsCutBackToACornerWhereTheCrossingWallEndsToo) {
  // An 8.5 cm piece (a wall drawn from its last sighting, the rest cut by the view) reaching
  // 1.5 cm past the line of a wall that ends where they meet: an L corner. The same piece past
  // a wall that goes on through the meeting point keeps its end (as above).
  std::vector<MappedPlane> corner = {Mapped(1, {2.43, 2}, {2.515, 2}),
                                     Mapped(2, {2.5, 0.6}, {2.5, 2})};
  SnapEndsToCorners(&corner, kRadius);
  ExpectAt(Hi(corner[0]), {2.5, 2});
  ExpectAt(Lo(corner[0]), {2.43, 2});
  std::vector<MappedPlane> through = {Mapped(1, {2.43, 2}, {2.515, 2}),
                                      Mapped(2, {2.5, 0.6}, {2.5, 3.4})};
  SnapEndsToCorners(&through, kRadius);
  ExpectAt(Hi(through[0]), {2.515, 2});
}

TEST(MapCorners, ALineThroughAWallsMiddleIsNotItsCorner) {
  // A 0.2 m door jamb across a thin partition's line, which ends at the jamb's middle: the
  // partition meets the jamb there, but neither jamb end is cut back to it.
  std::vector<MappedPlane> planes = {Mapped(1, {2.9, 0.6}, {3.1, 0.6}),
                                     Mapped(2, {3, 0.6}, {3, 2.5})};
  SnapEndsToCorners(&planes, kRadius);
  ExpectAt(Lo(planes[0]), {2.9, 0.6});
  ExpectAt(Hi(planes[0]), {3.1, 0.6});
  ExpectAt(Lo(planes[1]), {3, 0.6});
}

TEST(MapCorners, ALineCrossingAWallMoreThanAQuarterInIsNotItsCorner) {
  std::vector<MappedPlane> planes = {Mapped(1, {2.9, 0.6}, {3.2, 0.6}),
                                     Mapped(2, {3, 0.6}, {3, 2.5})};
  SnapEndsToCorners(&planes, kRadius);
  ExpectAt(Lo(planes[0]), {2.9, 0.6});
}

TEST(MapCorners, AShortPieceBesideACrossingLineMovesOnlyItsNearEnd) {
  // A 6 cm piece 1 cm short of a line at its high end: its low end is 7 cm from the same
  // line, and moving it there would fold the piece over.
  std::vector<MappedPlane> planes = {Mapped(1, {3.93, 0}, {3.99, 0}), Mapped(2, {4, -1}, {4, 1})};
  SnapEndsToCorners(&planes, kRadius);
  ExpectAt(Lo(planes[0]), {3.93, 0});
  ExpectAt(Hi(planes[0]), {4, 0});
}

TEST(MapCorners, TheNearestCrossingLineWins) {
  // A wall 2 cm thick seen from both sides: the end 3 cm short of its near face.
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.97, 0}), Mapped(2, {4, -1}, {4, 1}),
                                     Mapped(3, {4.02, 1}, {4.02, -1})};
  SnapEndsToCorners(&planes, kRadius);
  ExpectAt(Hi(planes[0]), {4, 0});
}

TEST(MapCorners, TheResultDoesNotDependOnTheWallsOrder) {
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.97, 0}), Mapped(2, {4, 0.03}, {4, 3}),
                                     Mapped(3, {0.02, 0.04}, {0.02, 3}),
                                     Mapped(4, {3.96, 3}, {0.05, 3})};
  std::vector<MappedPlane> reversed(planes.rbegin(), planes.rend());
  SnapEndsToCorners(&planes, kRadius);
  SnapEndsToCorners(&reversed, kRadius);
  std::reverse(reversed.begin(), reversed.end());
  for (size_t i = 0; i < planes.size(); ++i) {
    for (int v = 0; v < 4; ++v) EXPECT_EQ(planes[i].vertices[v], reversed[i].vertices[v]);
  }
  ExpectAt(Lo(planes[0]), {0.02, 0});  // the loop's four corners
  ExpectAt(Hi(planes[1]), {4, 3});
  ExpectAt(Hi(planes[3]), {0.02, 3});
}

TEST(MapCorners, RadiusZeroAndPlanesThatAreNotWallsAreLeftAlone) {
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, {3.97, 0}), Mapped(2, {4, 0.03}, {4, 3})};
  EXPECT_EQ(SnapEndsToCorners(&planes, 0.0), 0);
  ExpectAt(Hi(planes[0]), {3.97, 0});
  MappedPlane floor = Mapped(3, {4, -1}, {4, 1});
  floor.normal = Eigen::Vector3d::UnitZ();
  std::vector<MappedPlane> with_floor = {Mapped(1, {0, 0}, {3.97, 0}), floor};
  EXPECT_EQ(SnapEndsToCorners(&with_floor, kRadius), 0);
}

}  // namespace
}  // namespace relplane::mapper
