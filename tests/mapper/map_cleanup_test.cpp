// §II.D end, on the published map: a wall seen as a second rltplane lying inside another on the
// same line, or sharing most of itself with it, is shown once; what "the same line" allows
// depends on how well the piece's orientation is known, which is by its length.
#include "published_map/map_cleanup.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;

// A mapped wall from a to b (the normal on the left of a -> b), 2.5 m high. Its direction
// (MappedPlane's lo -> hi) is b -> a.
MappedPlane Mapped(int64_t id, const Vector2d& a, const Vector2d& b, int64_t observations) {
  MappedPlane m;
  m.id = id;
  const Vector2d t = (b - a).normalized();
  m.normal = Eigen::Vector3d(-t.y(), t.x(), 0.0);
  m.d = -m.normal.head<2>().dot(a);
  m.vertices = {{b.x(), b.y(), 0.0}, {a.x(), a.y(), 0.0}, {a.x(), a.y(), 2.5}, {b.x(), b.y(), 2.5}};
  const Vector2d mid = 0.5 * (a + b);
  m.centroid = Eigen::Vector3d(mid.x(), mid.y(), 1.25);
  m.observations = observations;
  m.both_ends_known = m.end_known[0] = m.end_known[1] = true;
  return m;
}

// A piece of `length` whose middle lies on the wall y = 2 at x = 3, turned by `degrees`.
MappedPlane Piece(int64_t id, double length, double degrees) {
  const double a = degrees * M_PI / 180.0;
  const Vector2d mid(3.0, 2.0), t(std::cos(a), std::sin(a));
  return Mapped(id, mid - 0.5 * length * t, mid + 0.5 * length * t, 14);
}

bool Kept(const std::vector<MappedPlane>& planes, int64_t id) {
  return std::any_of(planes.begin(), planes.end(),
                     [id](const MappedPlane& m) { return m.id == id; });
}

// Walls 1 and 2 both stay on the map.
void ExpectBothStay(std::vector<MappedPlane> planes) {
  MergeDuplicateWalls(&planes);
  EXPECT_TRUE(Kept(planes, 1));
  EXPECT_TRUE(Kept(planes, 2));
}

TEST(MapCleanup, ASliverBesideADiagonalWallsEndIsTheWall) {
  // 45 degrees: a 2 cm sliver 9 cm across the wall's line and 7-9 cm past its end lies
  // 0.11-0.13 m outside the wall's box in y (the nearby walls are looked up by their boxes, on
  // a grid with a cell border at y = 4).
  const Vector2d t = Vector2d(1, 1).normalized(), n(-t.y(), t.x());
  const Vector2d b = Vector2d(3.89, 3.89);  // its box widened by 0.1 m stops short of y = 4
  const Vector2d across = 0.09 * n;
  std::vector<MappedPlane> planes = {Mapped(1, {0, 0}, b, 200),
                                     Mapped(2, b + 0.07 * t + across, b + 0.09 * t + across, 14)};
  MergeDuplicateWalls(&planes);
  EXPECT_TRUE(Kept(planes, 1));
  EXPECT_FALSE(Kept(planes, 2));
}

TEST(MapCleanup, AShortPieceInsideAWallIsTheWallWhateverItsFitsTurn) {
  // A 0.2 m sliver of the wall beside a door jamb, its fit 7 degrees off (the jamb's points):
  // its ends lie within 1.3 cm of the wall's line.
  std::vector<MappedPlane> planes = {Mapped(1, {0, 2}, {5, 2}, 200), Piece(2, 0.2, 7.0)};
  MergeDuplicateWalls(&planes);
  EXPECT_TRUE(Kept(planes, 1));
  EXPECT_FALSE(Kept(planes, 2));
}

TEST(MapCleanup, AWallLyingInsideAnotherIsThatWallHoweverOftenItWasSeen) {
  // A wall's second rltplane (made from a sighting fitted off while turning in place, then
  // seen as often as the first): it lies inside the first, 0.13 m short of its end, with one
  // sighting more. It is the same wall, shown once, over the whole extent seen.
  std::vector<MappedPlane> planes = {Mapped(1, {0, 2}, {2, 2}, 112),
                                     Mapped(2, {0.13, 2.005}, {2.01, 2.005}, 113)};
  MergeDuplicateWalls(&planes);
  EXPECT_TRUE(Kept(planes, 1));
  EXPECT_FALSE(Kept(planes, 2));
}

TEST(MapCleanup, OfTwoWallsEachInsideTheOtherTheBetterObservedStays) {
  std::vector<MappedPlane> planes = {Mapped(1, {0, 2}, {2, 2}, 112),
                                     Mapped(2, {0.05, 2.005}, {2.05, 2.005}, 113)};
  MergeDuplicateWalls(&planes);
  EXPECT_FALSE(Kept(planes, 1));
  EXPECT_TRUE(Kept(planes, 2));
}

TEST(MapCleanup, ALongerPieceTurnedAsMuchIsAnotherWall) {
  // A 1.2 m piece is fitted to a tenth of a degree: 7 degrees off is not the same wall (its
  // ends are 7 cm either side of the line).
  ExpectBothStay({Mapped(1, {0, 2}, {5, 2}, 200), Piece(2, 1.2, 7.0)});
}

TEST(MapCleanup, ADoorJambAtTheWallStays) {
  // The jamb of a door in the wall (x = 3, 0.1 m deep across y = 2): perpendicular, so never
  // the same line however short.
  ExpectBothStay({Mapped(1, {0, 2}, {5, 2}, 200), Mapped(2, {3, 1.95}, {3, 2.05}, 30)});
}

// The wall of `id` among `planes` (which must hold it).
const MappedPlane& Wall(const std::vector<MappedPlane>& planes, int64_t id) {
  return *std::find_if(planes.begin(), planes.end(),
                       [id](const MappedPlane& m) { return m.id == id; });
}

TEST(MapCleanup, TwoWallsSharingMostOfTheShorterAreOneWallOverBoth) {
  // 3 m of the side wall y = 2 seen as two rltplanes 2 mm apart: the better-observed one
  // stretches over the other's extent and takes its end there, unknown as it was.
  MappedPlane other = Mapped(2, {1, 2.002}, {6, 2.002}, 50);
  other.end_known[0] = false;  // x = 6
  std::vector<MappedPlane> planes = {Mapped(1, {0, 2}, {4, 2}, 200), other};
  MergeDuplicateWalls(&planes);
  ASSERT_EQ(planes.size(), 1u);
  const MappedPlane& wall = Wall(planes, 1);
  EXPECT_NEAR(wall.vertices[0].x(), 6.0, 1e-9);
  EXPECT_NEAR(wall.vertices[1].x(), 0.0, 1e-9);
  EXPECT_FALSE(wall.end_known[0]);
  EXPECT_TRUE(wall.end_known[1]);
  EXPECT_FALSE(wall.both_ends_known);
  EXPECT_EQ(wall.observations, 250);
}

TEST(MapCleanup, ThreePiecesOfAWallEachSharingMostOfTheNextAreOne) {
  // The last shares most of itself with the middle one, which the first stretches over.
  std::vector<MappedPlane> planes = {Mapped(1, {0, 2}, {3, 2}, 200),
                                     Mapped(2, {1.4, 2}, {4.4, 2}, 100),
                                     Mapped(3, {3.2, 2}, {5, 2}, 50)};
  MergeDuplicateWalls(&planes);
  ASSERT_EQ(planes.size(), 1u);
  EXPECT_NEAR(Wall(planes, 1).vertices[0].x(), 5.0, 1e-9);
  EXPECT_NEAR(Wall(planes, 1).vertices[1].x(), 0.0, 1e-9);
}

TEST(MapCleanup, PiecesEitherSideOfADoorFrameReachingPastItStay) {
  // Each reaches 0.2 m past the other's end, a small part of either.
  ExpectBothStay({Mapped(1, {0, 2}, {3.1, 2}, 200), Mapped(2, {2.9, 2}, {6, 2}, 150)});
}

TEST(MapCleanup, APartitionsTwoFacesStay) {
  // A thin partition seen from both sides: the same line, facing opposite ways.
  ExpectBothStay({Mapped(1, {0, 2}, {4, 2}, 200), Mapped(2, {4.5, 2}, {0.5, 2}, 150)});
}

TEST(MapCleanup, TwoStretchesOfAWallSharingPartWhereTheViewCutBothAreOne) {
  // hallway_out_and_back at 1 cm: a 12 m wall mapped on the way out from where the view's edge
  // cut it (x = 5.89) and on the way back up to where the view cut it (x = 6.15), 2 cm apart:
  // 0.26 m shared, a small part of either, but neither end there was ever a wall end.
  auto stretches = [](bool cut) {
    MappedPlane first = Mapped(1, {5.89, 2}, {13, 2}, 300);
    MappedPlane back = Mapped(2, {0, 2.02}, {6.15, 2.02}, 150);
    first.end_known[1] = back.end_known[0] = !cut;  // x = 5.89 and x = 6.15
    first.both_ends_known = back.both_ends_known = !cut;
    return std::vector<MappedPlane>{first, back};
  };
  std::vector<MappedPlane> planes = stretches(true);
  MergeDuplicateWalls(&planes);
  ASSERT_EQ(planes.size(), 1u);
  EXPECT_NEAR(Wall(planes, 1).vertices[0].x(), 13.0, 1e-9);
  EXPECT_NEAR(Wall(planes, 1).vertices[1].x(), 0.0, 1e-9);
  // The same two with those ends seen static are two walls that meet there.
  ExpectBothStay(stretches(false));
}

TEST(MapCleanup, AWallEndAnotherStretchRunsPastWithItsOwnEndCutIsNoEnd) {
  // Generated world 89 at 1 cm: a 6 m wall (x = 3.25, y 8-14) mapped from y = 14 to an end at
  // y = 8.66 taken for static, and again from its corner y = 8 to y = 9.05 where the view cut
  // it: 0.38 m shared, less than half of either. The second stretch saw the surface go on past
  // the first's end, so that end is none: one wall over both, its ends the corner and y = 14.
  auto stretches = [](bool cut) {
    MappedPlane far = Mapped(1, {0, 2}, {5.34, 2}, 300);  // x = 5.34: the end taken for static
    MappedPlane near = Mapped(2, {4.96, 2.002}, {6, 2.002}, 120);  // x = 4.96 cut by the view
    near.end_known[1] = !cut;                                      // vertex 1 is a
    near.both_ends_known = !cut;
    return std::vector<MappedPlane>{far, near};
  };
  std::vector<MappedPlane> planes = stretches(true);
  MergeDuplicateWalls(&planes);
  ASSERT_EQ(planes.size(), 1u);
  const MappedPlane& wall = Wall(planes, 1);
  EXPECT_NEAR(wall.vertices[0].x(), 6.0, 1e-9);
  EXPECT_NEAR(wall.vertices[1].x(), 0.0, 1e-9);
  EXPECT_TRUE(wall.both_ends_known);
  // Both ends in the shared stretch seen static: they contradict each other, and both stay.
  ExpectBothStay(stretches(false));
}

TEST(MapCleanup, APieceAtACornerGoesOnceTheWallIsDrawnOnToTheCorner) {
  // hallway_out_and_back at 1 cm, seed 23: a 6 cm piece of wall at the corner x = 4, reaching a
  // centimetre past it, beside the wall's own end drawn 9.5 cm short of the corner. Before the
  // wall is drawn on to the corner the piece lies beyond it (the crossing wall stands in the gap,
  // so the piece is not joined to it either); after, inside it.
  MappedPlane wall = Mapped(1, {0, 2}, {3.905, 2}, 300);
  wall.end_known[0] = false;  // x = 3.905
  wall.both_ends_known = false;
  MappedPlane piece = Mapped(2, {3.95, 2}, {4.01, 2}, 80);
  piece.end_known[0] = piece.end_known[1] = piece.both_ends_known = false;
  const MappedPlane crossing = Mapped(3, {4, 5}, {4, 2}, 200);
  std::vector<MappedPlane> merged_first = {wall, piece, crossing};
  MergeDuplicateWalls(&merged_first);
  EXPECT_TRUE(Kept(merged_first, 2));
  std::vector<MappedPlane> planes = {wall, piece, crossing};
  CleanUpWalls(&planes, PublishedMapOptions{}, FitOptions{});
  EXPECT_FALSE(Kept(planes, 2));
  ASSERT_TRUE(Kept(planes, 1));
  EXPECT_NEAR(Wall(planes, 1).vertices[0].x(), 4.0, 1e-9);
}

}  // namespace
}  // namespace relplane::mapper
