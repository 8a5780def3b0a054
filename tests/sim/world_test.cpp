// Generators build closed, consistent worlds; the true planes describe them.

#include "relplane/sim/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "relplane/sim/ray_caster.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

World Build(GeneratorSpec generator) {
  WorldOptions options;
  options.generators = {generator};
  return BuildWorld(options);
}

// Every rectangle is well formed and inside [0, height]; walls are vertical.
void ExpectConsistent(const World& world, double height) {
  for (const Rect& r : world.rects) {
    EXPECT_GT(r.u.norm(), 0.0);
    EXPECT_GT(r.v.norm(), 0.0);
    EXPECT_NEAR(r.u.dot(r.v), 0.0, 1e-12);
    for (const Eigen::Vector3d& c : r.Corners()) {
      EXPECT_GE(c.z(), -1e-12);
      EXPECT_LE(c.z(), height + 1e-12);
    }
  }
  EXPECT_EQ(CountWalls(world) + 2, static_cast<int>(world.rects.size())) << "floor + ceiling";
}

// Every wall's floor-plan end touches another wall: no loose ends. Walls shorter than
// `min_length` (door jambs, which stand free by design) are not checked.
void ExpectNoLooseEnds(const World& world, double min_length = 0.0) {
  auto on_segment = [](const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                       const Eigen::Vector2d& b) {
    const Eigen::Vector2d e = b - a;
    const double f = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    return (a + f * e - p).norm() < 1e-9;
  };
  for (size_t i = 0; i < world.rects.size(); ++i) {
    const Rect& r = world.rects[i];
    if (std::abs(r.Normal().z()) > 0.1 || r.u.norm() < min_length) continue;
    const Eigen::Vector2d ends[2] = {r.origin.head<2>(), (r.origin + r.u).head<2>()};
    for (const Eigen::Vector2d& end : ends) {
      bool touches = false;
      for (size_t j = 0; j < world.rects.size() && !touches; ++j) {
        const Rect& o = world.rects[j];
        if (j == i || std::abs(o.Normal().z()) > 0.1) continue;
        touches = on_segment(end, o.origin.head<2>(), (o.origin + o.u).head<2>());
      }
      EXPECT_TRUE(touches) << "wall " << i << " end (" << end.transpose() << ") is loose";
    }
  }
}

// Horizontal rays at sensor height from `inside` all end on a wall: the plan is closed.
void ExpectClosedAround(const World& world, const Eigen::Vector2d& inside) {
  RayCaster caster(world);
  for (int i = 0; i < 720; ++i) {
    const double a = 2 * kPi * i / 720.0;
    const Hit h = caster.CastOneBruteForce(Eigen::Vector3d(inside.x(), inside.y(), 1.0),
                                           Eigen::Vector3d(std::cos(a), std::sin(a), 0.0), 1e3);
    ASSERT_GE(h.rect, 0) << "ray at " << a << " rad from " << inside.transpose() << " escapes";
    EXPECT_LT(std::abs(world.rects[h.rect].Normal().z()), 0.1);
  }
}

TEST(Generators, StraightHallwayIsAClosedBox) {
  const World world = Build(StraightHallwayParams{});
  EXPECT_EQ(CountWalls(world), 4);
  ExpectConsistent(world, 2.5);
  ExpectNoLooseEnds(world);
  ExpectClosedAround(world, {0.0, 0.0});
  ExpectClosedAround(world, {12.0, 0.5});
}

TEST(Generators, HallwayLoopIsClosedAndStartsInTheCorridor) {
  const World world = Build(HallwayLoopParams{});
  EXPECT_EQ(CountWalls(world), 8);
  ExpectConsistent(world, 2.5);
  ExpectNoLooseEnds(world);
  // The centre-line corners of the default 16 x 10 loop, 2 m wide.
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0, 0), Eigen::Vector2d(14, 0),
                                   Eigen::Vector2d(14, 8), Eigen::Vector2d(0, 8)}) {
    ExpectClosedAround(world, p);
    // One metre from the nearest walls on the centre line.
    RayCaster caster(world);
    for (const Eigen::Vector3d& d : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                     Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, -1, 0)}) {
      const Hit h = caster.CastOneBruteForce(Eigen::Vector3d(p.x(), p.y(), 1.0), d, 100.0);
      EXPECT_GE(h.range, 1.0 - 1e-12);
    }
  }
}

// The paper's Fig. 5: at a corner, facing the end of the hallway, one partial wall is in view.
TEST(Generators, HallwayLoopCornerShowsOneWall) {
  const World world = Build(HallwayLoopParams{});
  RayCaster caster(world);
  const RayGrid grid = RayGrid::Pinhole(160, 120, kPi / 2, kPi / 3);
  std::vector<Hit> hits;
  caster.Cast({14.0, 0.0, 1.0}, 0.0, grid, 8.0, &hits);
  std::set<int> walls;
  for (const Hit& h : hits) {
    if (h.rect >= 0 && std::abs(world.rects[h.rect].Normal().z()) < 0.1) walls.insert(h.rect);
  }
  EXPECT_EQ(walls.size(), 1u);
}

TEST(Generators, OfficeRoomsAreClosedAndJoinedByDoors) {
  for (double frame : {0.1, 0.0}) {
    OfficeParams p;
    p.frame_depth = frame;
    const World world = Build(p);
    ExpectConsistent(world, 2.5);
    ExpectNoLooseEnds(world, 0.15);
    // 4 outer walls; 7 inner walls, each two pieces + lintel (+ two jambs).
    EXPECT_EQ(CountWalls(world), 4 + 7 * (frame > 0 ? 5 : 3));
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 2; ++j) ExpectClosedAround(world, {5.0 * i, 4.0 * j});
    }
    // From room (0, 0) a ray through the door reaches room (1, 0).
    RayCaster caster(world);
    const Hit h = caster.CastOneBruteForce({0, 0, 1}, {1, 0, 0}, 100.0);
    EXPECT_NEAR(h.range, 12.5, 1e-9) << "through both doors to the far outer wall";
  }
}

TEST(World, LiteralWallsAndFloorCeilingBox) {
  WorldOptions options;
  options.generators.clear();
  options.walls = {{{0, 0}, {4, 0}, 0.0, -1.0}, {{4, 0}, {4, 3}, 0.5, 1.0}};
  options.height = 3.0;
  const World world = BuildWorld(options);
  ASSERT_EQ(world.rects.size(), 4u);
  EXPECT_NEAR(world.rects[0].v.z(), 3.0, 1e-12) << "default wall height = world height";
  EXPECT_NEAR(world.rects[1].origin.z(), 0.5, 1e-12);
  EXPECT_NEAR(world.rects[1].v.z(), 1.0, 1e-12);
  EXPECT_NEAR(world.rects[2].Normal().z(), 1.0, 1e-12) << "the floor faces up";
  EXPECT_NEAR(world.rects[3].Normal().z(), -1.0, 1e-12) << "the ceiling faces down";
  EXPECT_NEAR(world.rects[3].origin.z(), 3.0, 1e-12);
  EXPECT_NEAR(world.rects[2].u.x() * world.rects[2].v.y(), 12.0, 1e-12) << "4 x 3 box";
}

TEST(World, TruePlanesCarryEquationsAndCorners) {
  const World world = Build(OfficeParams{});
  const std::vector<TruePlane> planes = TruePlanes(world);
  ASSERT_EQ(planes.size(), world.rects.size());
  for (size_t i = 0; i < planes.size(); ++i) {
    const TruePlane& p = planes[i];
    EXPECT_EQ(p.id, static_cast<int>(i));
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12);
    for (const Eigen::Vector3d& c : p.corners) EXPECT_NEAR(p.normal.dot(c) + p.d, 0.0, 1e-9);
    EXPECT_NEAR(p.normal.dot(p.centroid) + p.d, 0.0, 1e-9);
    // Corners go round the rectangle: opposite sides equal, adjacent sides perpendicular.
    EXPECT_NEAR(((p.corners[1] - p.corners[0]) - (p.corners[2] - p.corners[3])).norm(), 0, 1e-12);
    EXPECT_NEAR((p.corners[1] - p.corners[0]).dot(p.corners[3] - p.corners[0]), 0, 1e-9);
  }
}

TEST(Simulation, PosesAndTimesFollowTheRate) {
  SimOptions options;
  options.rate_hz = 30.0;
  options.trajectory.waypoints = {{0, 0}, {3, 0}};
  Simulation sim(options);
  EXPECT_EQ(sim.NumIterations(), 91);
  EXPECT_EQ(sim.Utime(0), 0);
  EXPECT_EQ(sim.Utime(30), 1000000);
  EXPECT_EQ(sim.Utime(1), 33333);
  const Eigen::Isometry3d first = sim.SensorPose(0);
  EXPECT_TRUE(first.rotation().isIdentity(1e-12));
  EXPECT_NEAR((first.translation() - Eigen::Vector3d(0, 0, 1.0)).norm(), 0, 1e-12);
  EXPECT_NEAR(sim.SensorPose(90).translation().x(), 3.0, 1e-9);
  EXPECT_GT(sim.Frame(0).points.size(), 10000u);
}

}  // namespace
}  // namespace relplane::sim
