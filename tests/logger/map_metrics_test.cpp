// Map metrics against hand-made worlds and maps with known answers.
#include "relplane/eval/map_metrics.hpp"

#include <gtest/gtest.h>

#include "fixtures.hpp"

namespace relplane::eval {
namespace {

using testing::Floor;
using testing::LoopInRoom;
using testing::Room;
using testing::Wall;

// The room's four walls as a mapper would report them, ids 10..13.
MapSnapshot PerfectMap() {
  MapSnapshot map;
  map.planes = {Wall(10, {-1, -2}, {5, -2}), Wall(11, {5, -2}, {5, 2}), Wall(12, {5, 2}, {-1, 2}),
                Wall(13, {-1, 2}, {-1, -2})};
  return map;
}

MapMetrics Score(const MapSnapshot& map, const MapSnapshot& world = Room()) {
  return ComputeMapMetrics(world, map, LoopInRoom(), EvalOptions{});
}

TEST(MapMetrics, PerfectMapMatchesEveryWallAndIgnoresTheFloor) {
  MapSnapshot map = PerfectMap();
  map.planes.push_back(Floor(20));
  const MapMetrics m = Score(map);
  EXPECT_TRUE(m.has_truth);
  EXPECT_EQ(m.true_walls, 4);
  EXPECT_EQ(m.expected_walls, 4);
  EXPECT_EQ(m.mapped_planes, 5);
  EXPECT_EQ(m.mapped_walls, 4);
  EXPECT_EQ(m.walls_mapped, 4);
  EXPECT_EQ(m.duplicates, 0);
  EXPECT_EQ(m.spurious, 0);
  EXPECT_EQ(m.missed, 0);
  EXPECT_NEAR(m.normal_error_deg.max, 0.0, 1e-6);
  EXPECT_NEAR(m.offset_error_m.max, 0.0, 1e-9);
  EXPECT_NEAR(m.endpoint_error_m.max, 0.0, 1e-9);
  ASSERT_EQ(m.walls.size(), 4u);
  EXPECT_EQ(m.walls[2].mapped_ids, std::vector<int64_t>{12});
  EXPECT_NEAR(m.walls[2].overlap_m, 6.0, 1e-9);
}

TEST(MapMetrics, DuplicatedWallIsCountedOnceAsADuplicate) {
  MapSnapshot map = PerfectMap();
  // A second, shorter plane on the south wall, 0.1 m off: the same wall mapped twice.
  map.planes.push_back(Wall(14, {0, -1.9}, {3, -1.9}));
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.walls_mapped, 4);
  EXPECT_EQ(m.duplicates, 1);
  EXPECT_EQ(m.spurious, 0);
  // The longer overlap is the best match; errors are the best match's.
  EXPECT_EQ(m.walls[0].mapped_ids, (std::vector<int64_t>{10, 14}));
  EXPECT_NEAR(m.walls[0].offset_error_m, 0.0, 1e-9);
}

TEST(MapMetrics, APartitionsOtherFaceIsNoDuplicate) {
  MapSnapshot map = PerfectMap();
  // The south wall as seen from beyond it (its normal the other way): the wall's other face.
  map.planes.push_back(Wall(14, {3, -2.02}, {0, -2.02}));
  // And a second plane facing the same way as the first: a duplicate still.
  map.planes.push_back(Wall(15, {0.5, -1.95}, {2.5, -1.95}));
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.walls[0].mapped_ids.size(), 3u);
  EXPECT_EQ(m.other_faces, 1);
  EXPECT_EQ(m.duplicates, 1);
  EXPECT_EQ(m.fragments, 0);
}

TEST(MapMetrics, ThreeCopiesOfOneWallAreTwoDuplicates) {
  MapSnapshot map = PerfectMap();
  map.planes.push_back(Wall(14, {0, -1.9}, {3, -1.9}));
  map.planes.push_back(Wall(15, {3, -2.05}, {4.5, -2.05}));
  EXPECT_EQ(Score(map).duplicates, 2);
}

TEST(MapMetrics, AWallMappedInDisjointPiecesHasFragmentsNotDuplicates) {
  MapSnapshot map = PerfectMap();
  // The south wall as three pieces, as rooms along it see it between partitions.
  map.planes[0] = Wall(10, {-1, -2}, {1, -2});
  map.planes.push_back(Wall(14, {1.1, -2}, {3, -2}));
  map.planes.push_back(Wall(15, {3.1, -2.02}, {5, -2.02}));
  // ... and one more plane over part of the first piece: that part mapped twice.
  map.planes.push_back(Wall(16, {-0.5, -1.95}, {0.5, -1.95}));
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.walls_mapped, 4);
  EXPECT_EQ(m.fragments, 2);
  EXPECT_EQ(m.duplicates, 1);
  EXPECT_EQ(m.spurious, 0);
}

TEST(MapMetrics, AMappedDoorJambIsNeitherScoredNorSpurious) {
  MapSnapshot world = Room();
  world.planes.push_back(Wall(7, {2, -2}, {2, -1.9}));  // a 0.1 m jamb on the south wall
  MapSnapshot map = PerfectMap();
  map.planes.push_back(Wall(40, {2.01, -2}, {2.01, -1.9}));  // the jamb, mapped
  map.planes.push_back(Wall(41, {3, -1.2}, {3, -1.1}));      // a jamb where there is none
  const MapMetrics m = Score(map, world);
  EXPECT_EQ(m.true_walls, 4);
  EXPECT_EQ(m.on_short_walls, 1);
  EXPECT_EQ(m.spurious_ids, std::vector<int64_t>{41});
}

TEST(MapMetrics, APilasterFaceMappedOnItGoesToTheFaceNotTheLongerWallBehind) {
  MapSnapshot world = Room();
  world.planes.push_back(Wall(7, {1.8, -1.7}, {2.3, -1.7}));  // a face 0.3 m out of the south wall
  MapSnapshot map = PerfectMap();
  // The face mapped 1 cm off and a little long: it lies along more of the south wall than of
  // the face, but it is the face.
  map.planes.push_back(Wall(40, {1.78, -1.71}, {2.32, -1.71}));
  const MapMetrics m = Score(map, world);
  ASSERT_EQ(m.walls.size(), 5u);
  EXPECT_EQ(m.walls[0].mapped_ids, std::vector<int64_t>{10});
  EXPECT_EQ(m.walls[4].mapped_ids, std::vector<int64_t>{40});
  EXPECT_NEAR(m.walls[4].offset_error_m, 0.01, 1e-9);
  EXPECT_EQ(m.duplicates, 0);
  EXPECT_LT(m.offset_error_m.max, 0.02);
}

TEST(MapMetrics, AShortFaceMappedOnItIsNotADuplicateOfTheWallBehind) {
  // A partition's 0.25 m end face 0.2 m out from the south wall, too short to be scored, mapped
  // 3 cm off: it lies along the south wall too, and was counted as the south wall mapped twice
  // (generated world 232, noise-free: two duplicates that were partition ends).
  MapSnapshot world = Room();
  world.planes.push_back(Wall(7, {1.8, -1.8}, {2.05, -1.8}));
  MapSnapshot map = PerfectMap();
  map.planes.push_back(Wall(40, {1.8, -1.77}, {2.05, -1.77}));
  const MapMetrics m = Score(map, world);
  EXPECT_EQ(m.true_walls, 4);
  EXPECT_EQ(m.duplicates, 0);
  EXPECT_EQ(m.on_short_walls, 1);
  EXPECT_EQ(m.walls[0].mapped_ids, std::vector<int64_t>{10});
  // Mapped on neither, nearer the south wall, it is the south wall's duplicate, as before.
  map.planes.back() = Wall(40, {1.8, -1.92}, {2.05, -1.92});
  EXPECT_EQ(Score(map, world).duplicates, 1);
}

TEST(MapMetrics, AWallMappedPastAPilasterStillGoesToTheWall) {
  MapSnapshot world = Room();
  world.planes.push_back(Wall(7, {1.8, -1.7}, {2.3, -1.7}));
  MapSnapshot map = PerfectMap();
  map.planes[0] = Wall(10, {-1, -1.8}, {5, -1.8});  // the south wall, 0.2 m off: nearer the face
  const MapMetrics m = Score(map, world);
  EXPECT_EQ(m.walls[0].mapped_ids, std::vector<int64_t>{10});
  EXPECT_TRUE(m.walls[4].mapped_ids.empty());
  EXPECT_NEAR(m.walls[0].offset_error_m, 0.2, 1e-9);
}

TEST(MapMetrics, PlanesMatchingNoWallAreSpurious) {
  MapSnapshot map = PerfectMap();
  map.planes.push_back(Wall(30, {1, -1}, {2, 1}));        // diagonal across the room
  map.planes.push_back(Wall(31, {-1, -1.4}, {5, -1.4}));  // parallel, 0.6 m off the south wall
  map.planes.push_back(Wall(32, {7, -2}, {9, -2}));       // on the south wall's line, past its end
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.spurious, 3);
  EXPECT_EQ(m.spurious_ids, (std::vector<int64_t>{30, 31, 32}));
  EXPECT_EQ(m.duplicates, 0);
  EXPECT_EQ(m.walls_mapped, 4);
}

TEST(MapMetrics, SeenButUnmappedWallIsMissed) {
  MapSnapshot map = PerfectMap();
  map.planes.erase(map.planes.begin() + 1);  // the east wall, which the loop faces
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.walls_mapped, 3);
  EXPECT_EQ(m.expected_walls, 4);
  EXPECT_EQ(m.missed, 1);
  EXPECT_TRUE(m.walls[1].expected);
  EXPECT_TRUE(m.walls[1].mapped_ids.empty());
}

// A plane over 0.1 m of the 6 m north wall matches it but does not map it: it is missed
// (partly mapped), as the wall is covered over less than half of what was seen of it.
TEST(MapMetrics, AWallCoveredOverLessThanHalfItsVisibleLengthIsMissed) {
  MapSnapshot map = PerfectMap();
  map.planes[2] = Wall(12, {2.1, 2}, {2.0, 2});
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.walls[2].mapped_ids, std::vector<int64_t>{12});
  EXPECT_FALSE(m.walls[2].mapped);
  EXPECT_NEAR(m.walls[2].mapped_length_m, 0.1, 1e-9);
  EXPECT_GT(m.walls[2].visible_length_m, 5.5);
  EXPECT_LT(m.walls[2].coverage, 0.05);
  EXPECT_EQ(m.walls_mapped, 3);
  EXPECT_EQ(m.partly_mapped, 1);
  EXPECT_EQ(m.missed, 1);
  // Over 60% of it, from one end, it is mapped.
  map.planes[2] = Wall(12, {5, 2}, {1.3, 2});
  const MapMetrics n = Score(map);
  EXPECT_TRUE(n.walls[2].mapped);
  EXPECT_NEAR(n.walls[2].coverage, 3.7 / 6.0, 0.05);
  EXPECT_EQ(n.walls_mapped, 4);
  EXPECT_EQ(n.missed, 0);
}

// An outer wall mapped in three correct fragments has its end points where its ends are.
TEST(MapMetrics, EndPointsAreScoredOverAWallsFragmentsTogether) {
  MapSnapshot map = PerfectMap();
  map.planes[0] = Wall(10, {-1, -2}, {1, -2});
  map.planes.push_back(Wall(14, {1.2, -2}, {3, -2}));
  map.planes.push_back(Wall(15, {3.2, -2}, {5, -2}));
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.walls[0].mapped_ids.size(), 3u);
  EXPECT_NEAR(m.walls[0].endpoint_error_m[0], 0.0, 1e-9);
  EXPECT_NEAR(m.walls[0].endpoint_error_m[1], 0.0, 1e-9);
  EXPECT_NEAR(m.endpoint_error_m.max, 0.0, 1e-9);
  EXPECT_NEAR(m.walls[0].mapped_length_m, 5.6, 1e-9);
  EXPECT_TRUE(m.walls[0].mapped);
}

// The far end of a wall the sensor never came near is not scored: it could not be mapped.
TEST(MapMetrics, AnEndNeverSeenIsNotScored) {
  MapSnapshot world;
  world.planes = {Wall(0, {-1, -1}, {30, -1})};  // a long side wall, its far end out of range
  std::vector<PoseSample> truth;
  for (int i = 0; i <= 20; ++i) truth.push_back(testing::Pose(i, 0.1 * i, 0.0, 0.0));
  MapSnapshot map;
  map.planes = {Wall(10, {-1, -1}, {9, -1})};
  const MapMetrics m = ComputeMapMetrics(world, map, truth, EvalOptions{});
  ASSERT_EQ(m.walls.size(), 1u);
  // The near end (x = -1) is behind the sensor from every pose: neither end was seen.
  EXPECT_TRUE(std::isnan(m.walls[0].endpoint_error_m[0]));
  EXPECT_TRUE(std::isnan(m.walls[0].endpoint_error_m[1]));
  EXPECT_TRUE(std::isnan(m.endpoint_error_m.max));
  EXPECT_TRUE(m.walls[0].mapped);  // what was seen (x up to about 10 m) is covered
}

TEST(MapMetrics, WallsOutOfSightAreNotExpected) {
  MapSnapshot world = Room();
  world.planes.push_back(Wall(5, {-1, -3}, {5, -3}));  // behind the south wall: occluded
  world.planes.push_back(Wall(6, {40, -2}, {40, 2}));  // far beyond the sensor's range
  const MapMetrics m = Score(PerfectMap(), world);
  EXPECT_EQ(m.true_walls, 6);
  EXPECT_EQ(m.expected_walls, 4);
  EXPECT_EQ(m.missed, 0);
  EXPECT_FALSE(m.walls[4].expected);
  EXPECT_FALSE(m.walls[5].expected);
}

TEST(MapMetrics, WallsBehindTheSensorAreNotExpected) {
  // The robot only drives east along y = 0 facing +x: the west wall stays behind it.
  std::vector<PoseSample> truth;
  for (int i = 0; i <= 30; ++i) truth.push_back(testing::Pose(i, 0.1 * i, 0.0, 0.0));
  const MapMetrics m = ComputeMapMetrics(Room(), MapSnapshot{}, truth, EvalOptions{});
  ASSERT_EQ(m.walls.size(), 4u);
  EXPECT_TRUE(m.walls[0].expected);   // south: within the 90 degree view ahead
  EXPECT_TRUE(m.walls[1].expected);   // east, ahead
  EXPECT_TRUE(m.walls[2].expected);   // north
  EXPECT_FALSE(m.walls[3].expected);  // west, behind
  EXPECT_EQ(m.missed, 3);
  // A narrower field of view sees only the wall ahead.
  EvalOptions narrow;
  narrow.visibility.hfov_deg = 20.0;
  const MapMetrics n = ComputeMapMetrics(Room(), MapSnapshot{}, truth, narrow);
  EXPECT_EQ(n.expected_walls, 1);
  EXPECT_TRUE(n.walls[1].expected);
}

TEST(MapMetrics, WallsAboveTheSensorNeitherCountNorHide) {
  MapSnapshot world = Room();
  // A lintel-like strip 2.0-2.5 m high across the room at x = 2: the sensor at 1 m passes under.
  PlaneRecord lintel = Wall(5, {2, -2}, {2, 2});
  for (Eigen::Vector3d& v : lintel.vertices) v.z() = v.z() > 1.0 ? 2.5 : 2.0;
  world.planes.push_back(lintel);
  std::vector<PoseSample> truth;
  for (int i = 0; i <= 10; ++i) truth.push_back(testing::Pose(i, 0.1 * i, 0.0, 0.0));
  const MapMetrics m = ComputeMapMetrics(world, MapSnapshot{}, truth, EvalOptions{});
  EXPECT_EQ(m.true_walls, 4);
  EXPECT_TRUE(m.walls[1].expected);  // the east wall, seen under the strip
  // Raised to the sensor's height the strip is a wall and hides the east wall.
  for (Eigen::Vector3d& v : world.planes.back().vertices) v.z() = v.z() > 2.2 ? 2.5 : 0.0;
  const MapMetrics n = ComputeMapMetrics(world, MapSnapshot{}, truth, EvalOptions{});
  EXPECT_EQ(n.true_walls, 5);
  EXPECT_FALSE(n.walls[1].expected);
}

TEST(MapMetrics, ErrorsOfAnOffsetAndOverlongWall) {
  MapSnapshot map = PerfectMap();
  // The south wall 0.05 m inside the room and 0.2 m too long at its east end.
  map.planes[0] = Wall(10, {-1, -1.95}, {5.2, -1.95});
  // The east wall turned by 2 degrees about its midpoint.
  const double half = 2.0, tilt = 2.0 * M_PI / 180.0;
  map.planes[1] = Wall(11, {5 + half * std::sin(tilt), -half * std::cos(tilt)},
                       {5 - half * std::sin(tilt), half * std::cos(tilt)});
  const MapMetrics m = Score(map);
  EXPECT_EQ(m.walls_mapped, 4);
  EXPECT_NEAR(m.walls[0].offset_error_m, 0.05, 1e-6);
  EXPECT_NEAR(m.walls[0].normal_error_deg, 0.0, 1e-6);
  // One end is only 0.05 m off, the other also 0.2 m beyond the wall (order: along the wall).
  const double* ends = m.walls[0].endpoint_error_m;
  EXPECT_NEAR(std::min(ends[0], ends[1]), 0.05, 1e-6);
  EXPECT_NEAR(std::max(ends[0], ends[1]), std::hypot(0.05, 0.2), 1e-6);
  EXPECT_NEAR(m.walls[1].normal_error_deg, 2.0, 1e-4);
  EXPECT_NEAR(m.walls[1].offset_error_m, 0.0, 1e-6);
  EXPECT_NEAR(m.normal_error_deg.max, 2.0, 1e-4);
  EXPECT_NEAR(m.endpoint_error_m.max, std::hypot(0.05, 0.2), 1e-6);
}

TEST(MapMetrics, WallsOfMapsNeedAnExtent) {
  MapSnapshot map = PerfectMap();
  map.planes[0].vertices.resize(1);
  int64_t without_extent = 0;
  EXPECT_EQ(WallsOf(map.planes, &without_extent).size(), 3u);
  EXPECT_EQ(without_extent, 1);
  EXPECT_EQ(Score(map).mapped_without_extent, 1);
}

TEST(MapMetrics, WithoutTruthNothingIsSpurious) {
  const MapMetrics m = ComputeMapMetrics(MapSnapshot{}, PerfectMap(), {}, EvalOptions{});
  EXPECT_FALSE(m.has_truth);
  EXPECT_EQ(m.mapped_walls, 4);
  EXPECT_EQ(m.spurious, 0);
  EXPECT_EQ(m.true_walls, 0);
}

}  // namespace
}  // namespace relplane::eval
