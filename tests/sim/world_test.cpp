// Generators build closed, consistent worlds; the true planes describe them.

#include "relplane/sim/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "angles.hpp"
#include "relplane/sim/ray_caster.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::sim {
namespace {

using testing::kPi;

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

// recess_spacing 0 (the default) is the plain loop of before: outer and inner box, nothing else,
// whatever the other recess options say.
TEST(Generators, HallwayLoopWithoutRecessesIsThePlainLoop) {
  HallwayLoopParams p;
  p.recess_width = 2.0;
  p.recess_depth = 1.0;
  const World world = Build(p);
  using V = Eigen::Vector2d;
  const V outer[4] = {V(-1, -1), V(15, -1), V(15, 9), V(-1, 9)};
  const V inner[4] = {V(1, 1), V(13, 1), V(13, 7), V(1, 7)};
  ASSERT_EQ(CountWalls(world), 8);
  for (int i = 0; i < 8; ++i) {
    const V* c = i < 4 ? outer : inner;
    const Rect expected = Rect::Wall(c[i % 4], c[(i + 1) % 4], 0.0, 2.5);
    EXPECT_EQ(world.rects[i].origin, expected.origin) << i;
    EXPECT_EQ(world.rects[i].u, expected.u) << i;
    EXPECT_EQ(world.rects[i].v, expected.v) << i;
  }
}

// Two floor-plan segments share no stretch of a line and do not cross; meeting at an end is fine.
bool Overlap(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
             const Eigen::Vector2d& b1) {
  auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    return x.x() * y.y() - x.y() * y.x();
  };
  const Eigen::Vector2d da = a1 - a0, db = b1 - b0;
  constexpr double kEps = 1e-9;
  if (std::abs(cross(da, db)) < kEps) {
    if (std::abs(cross(da, b0 - a0)) > kEps * da.norm()) return false;  // parallel, apart
    const Eigen::Vector2d t = da.normalized();
    const double lo = std::max(0.0, std::min(t.dot(b0 - a0), t.dot(b1 - a0)));
    const double hi = std::min(da.norm(), std::max(t.dot(b0 - a0), t.dot(b1 - a0)));
    return hi - lo > kEps;
  }
  const double s = cross(b0 - a0, db) / cross(da, db);
  const double u = cross(b0 - a0, da) / cross(da, db);
  return s > kEps && s < 1 - kEps && u > kEps && u < 1 - kEps;
}

TEST(Generators, HallwayLoopRecessesOnTheOuterWalls) {
  HallwayLoopParams p;
  p.recess_spacing = 3.0;
  const World world = Build(p);
  // 16 m sides: recesses at 3, 6, 9, 12 m (15 m is within 1.5 m of the corner); 10 m sides: at
  // 3 and 6 m. Each recess adds a jamb, a back wall, a jamb and another wall piece.
  const int recesses = 2 * 4 + 2 * 2;
  EXPECT_EQ(CountWalls(world), 4 + 4 * recesses + 4);
  ExpectConsistent(world, 2.5);
  ExpectNoLooseEnds(world);
  for (const Eigen::Vector2d& q : {Eigen::Vector2d(0, 0), Eigen::Vector2d(14, 0),
                                   Eigen::Vector2d(14, 8), Eigen::Vector2d(0, 8)}) {
    ExpectClosedAround(world, q);
  }
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls;
  for (const Rect& r : world.rects) {
    if (std::abs(r.Normal().z()) < 0.1) {
      walls.emplace_back(r.origin.head<2>(), (r.origin + r.u).head<2>());
    }
  }
  for (size_t i = 0; i < walls.size(); ++i) {
    for (size_t j = i + 1; j < walls.size(); ++j) {
      EXPECT_FALSE(Overlap(walls[i].first, walls[i].second, walls[j].first, walls[j].second))
          << "walls " << i << " and " << j;
    }
  }
  // Back walls: 1 m long, 0.3 m outside the outer wall lines x = -1, x = 15, y = -1, y = 9, and
  // none within 1.5 m of a corner. Jambs: 0.3 m, across the outer wall line.
  int back_walls = 0, jambs = 0;
  for (const auto& [a, b] : walls) {
    const Eigen::Vector2d d = b - a;
    if (std::abs(d.norm() - p.recess_width) < 1e-9) {
      ++back_walls;
      const bool along_x = std::abs(d.y()) < 1e-12;
      const double line = along_x ? a.y() : a.x();
      const double lo = -1.0, hi = along_x ? 9.0 : 15.0;
      EXPECT_TRUE(std::abs(line - (lo - 0.3)) < 1e-9 || std::abs(line - (hi + 0.3)) < 1e-9)
          << a.transpose() << " -> " << b.transpose();
      const double s0 = along_x ? std::min(a.x(), b.x()) : std::min(a.y(), b.y());
      const double s1 = along_x ? std::max(a.x(), b.x()) : std::max(a.y(), b.y());
      EXPECT_GE(s0, -1.0 + 1.5 - 1e-9);
      EXPECT_LE(s1, (along_x ? 15.0 : 9.0) - 1.5 + 1e-9);
    } else if (std::abs(d.norm() - p.recess_depth) < 1e-9) {
      ++jambs;
    }
  }
  EXPECT_EQ(back_walls, recesses);
  EXPECT_EQ(jambs, 2 * recesses);
  // Through a recess (x from 2 to 3 m on the bottom wall) the robot sees its back wall, 0.3 m
  // beyond the outer wall line; beside it, the outer wall.
  RayCaster caster(world);
  const Hit h = caster.CastOneBruteForce({2.5, 0.0, 1.0}, {0, -1, 0}, 100.0);
  EXPECT_NEAR(h.range, 1.3, 1e-9);
  const Hit wall = caster.CastOneBruteForce({3.5, 0.0, 1.0}, {0, -1, 0}, 100.0);
  EXPECT_NEAR(wall.range, 1.0, 1e-9);
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
