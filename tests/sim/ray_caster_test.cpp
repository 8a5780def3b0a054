// Ray casting against analytic depths, occlusion, door frames, floor and ceiling, and the
// column index against brute force.

#include "relplane/sim/ray_caster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "angles.hpp"
#include "relplane/sim/generators.hpp"
#include "relplane/sim/world.hpp"

namespace relplane::sim {
namespace {

using testing::kDeg;
using testing::kPi;

RayGrid SmallGrid() { return RayGrid::Pinhole(32, 24, 90 * kDeg, 60 * kDeg); }

TEST(RayGrid, PinholeRaysSpanTheFieldOfView) {
  const RayGrid g = RayGrid::Pinhole(4, 2, 90 * kDeg, 60 * kDeg);
  ASSERT_EQ(g.directions.size(), 8u);
  for (const Eigen::Vector3d& d : g.directions) EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  // Pixel centres: leftmost column at y = tan(45°) * 3/4, top row at z = tan(30°) / 2.
  const Eigen::Vector3d top_left = g.directions[0] / g.directions[0].x();
  EXPECT_NEAR(top_left.y(), 0.75, 1e-12);
  EXPECT_NEAR(top_left.z(), std::tan(30 * kDeg) * 0.5, 1e-12);
  const Eigen::Vector3d bottom_right = g.directions[7] / g.directions[7].x();
  EXPECT_NEAR(bottom_right.y(), -0.75, 1e-12);
  EXPECT_NEAR(bottom_right.z(), -std::tan(30 * kDeg) * 0.5, 1e-12);
  // Every ray of a column shares its horizontal direction.
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 4; ++col) {
      const Eigen::Vector3d& d = g.directions[col * 2 + row];
      EXPECT_NEAR(d.head<2>().normalized().dot(g.column_directions[col]), 1.0, 1e-12);
    }
  }
}

// One wall at x = 5 (y in [-10, 10], z in [0, 3]) seen from a turned, displaced sensor: every
// ray's range is the analytic ray-plane distance where the hit lies on the wall, else a miss.
TEST(RayCaster, SingleWallMatchesAnalyticDepth) {
  World world;
  world.rects.push_back(Rect::Wall({5, -10}, {5, 10}, 0.0, 3.0));
  RayCaster caster(world);
  const RayGrid grid = SmallGrid();
  const Eigen::Vector3d origin(1.0, 2.0, 1.0);
  const double yaw = 20 * kDeg;
  std::vector<Hit> hits;
  caster.Cast(origin, yaw, grid, 8.0, &hits);
  int hit_count = 0;
  int miss_count = 0;
  for (size_t i = 0; i < hits.size(); ++i) {
    const Eigen::Vector3d d = RotateYaw(std::cos(yaw), std::sin(yaw), grid.directions[i]);
    const double t = (5.0 - origin.x()) / d.x();
    const Eigen::Vector3d p = origin + t * d;
    const bool expected = t > 0 && t <= 8.0 && p.z() >= 0 && p.z() <= 3 && std::abs(p.y()) <= 10;
    if (expected) {
      ASSERT_EQ(hits[i].rect, 0) << "ray " << i;
      EXPECT_NEAR(hits[i].range, t, 1e-9);
      ++hit_count;
    } else {
      EXPECT_EQ(hits[i].rect, -1) << "ray " << i;
      ++miss_count;
    }
  }
  // The wall's top edge and the missing floor leave both hits and misses in view.
  EXPECT_GT(hit_count, 100);
  EXPECT_GT(miss_count, 20);
}

TEST(RayCaster, MaxRangeCutsOffFarWalls) {
  World world;
  // Tall and wide enough to fill the whole view at 9 m.
  world.rects.push_back(Rect::Wall({9, -20}, {9, 20}, -10.0, 20.0));
  RayCaster caster(world);
  std::vector<Hit> hits;
  caster.Cast({0, 0, 1}, 0.0, SmallGrid(), 8.0, &hits);
  for (const Hit& h : hits) EXPECT_EQ(h.rect, -1);
  caster.Cast({0, 0, 1}, 0.0, SmallGrid(), 20.0, &hits);
  int hit_count = 0;
  for (const Hit& h : hits) hit_count += h.rect == 0 ? 1 : 0;
  EXPECT_EQ(hit_count, static_cast<int>(hits.size()));
}

// A near wall (x = 3, |y| <= 1) hides the far wall (x = 6) behind it, whatever the order of the
// rectangles in the world.
TEST(RayCaster, NearWallOccludesFarWall) {
  for (bool near_first : {true, false}) {
    World world;
    const Rect near = Rect::Wall({3, -1}, {3, 1}, 0.0, 3.0);
    const Rect far = Rect::Wall({6, -5}, {6, 5}, 0.0, 3.0);
    world.rects = near_first ? std::vector<Rect>{near, far} : std::vector<Rect>{far, near};
    const int near_id = near_first ? 0 : 1;
    const int far_id = 1 - near_id;
    RayCaster caster(world);
    const RayGrid grid = SmallGrid();
    const Eigen::Vector3d origin(0, 0, 1);
    std::vector<Hit> hits;
    caster.Cast(origin, 0.0, grid, 8.0, &hits);
    int near_hits = 0;
    int far_hits = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
      const Eigen::Vector3d& d = grid.directions[i];
      const Eigen::Vector3d at_near = origin + (3.0 / d.x()) * d;
      const Eigen::Vector3d at_far = origin + (6.0 / d.x()) * d;
      if (std::abs(at_near.y()) <= 1 && at_near.z() >= 0 && at_near.z() <= 3) {
        ASSERT_EQ(hits[i].rect, near_id);
        EXPECT_NEAR(hits[i].range, 3.0 / d.x(), 1e-9);
        ++near_hits;
      } else if (std::abs(at_far.y()) <= 5 && at_far.z() >= 0 && at_far.z() <= 3) {
        ASSERT_EQ(hits[i].rect, far_id);
        EXPECT_NEAR(hits[i].range, 6.0 / d.x(), 1e-9);
        ++far_hits;
      } else {
        EXPECT_EQ(hits[i].rect, -1);
      }
    }
    EXPECT_GT(near_hits, 20);
    EXPECT_GT(far_hits, 20);
  }
}

// Inside a closed box (hallway with floor and ceiling) every ray ends on the nearest of the
// six planes: floor and ceiling hits are checked analytically too.
TEST(RayCaster, ClosedHallwayHitsNearestOfSixPlanes) {
  WorldOptions options;
  options.height = 2.5;
  options.generators = {StraightHallwayParams{10.0, 2.0, -1.0, true}};
  const World world = BuildWorld(options);
  ASSERT_EQ(world.rects.size(), 6u);  // 4 walls, floor, ceiling
  RayCaster caster(world);
  const RayGrid grid = RayGrid::Pinhole(40, 30, 90 * kDeg, 100 * kDeg);
  const Eigen::Vector3d origin(2.0, 0.3, 1.0);
  const double yaw = -35 * kDeg;
  std::vector<Hit> hits;
  caster.Cast(origin, yaw, grid, 100.0, &hits);
  int floor_hits = 0;
  int ceiling_hits = 0;
  for (size_t i = 0; i < hits.size(); ++i) {
    const Eigen::Vector3d d = RotateYaw(std::cos(yaw), std::sin(yaw), grid.directions[i]);
    double best = std::numeric_limits<double>::infinity();
    auto consider = [&](double t) {
      if (t > 0) best = std::min(best, t);
    };
    consider((-1.0 - origin.x()) / d.x());
    consider((9.0 - origin.x()) / d.x());
    consider((-1.0 - origin.y()) / d.y());
    consider((1.0 - origin.y()) / d.y());
    const double t_floor = -origin.z() / d.z();
    const double t_ceiling = (2.5 - origin.z()) / d.z();
    consider(t_floor);
    consider(t_ceiling);
    ASSERT_GE(hits[i].rect, 0) << "a closed box has no gaps";
    EXPECT_NEAR(hits[i].range, best, 1e-9);
    if (hits[i].rect == 4) {
      EXPECT_NEAR(hits[i].range, t_floor, 1e-9);
      ++floor_hits;
    }
    if (hits[i].rect == 5) {
      EXPECT_NEAR(hits[i].range, t_ceiling, 1e-9);
      ++ceiling_hits;
    }
  }
  EXPECT_GT(floor_hits, 50);
  EXPECT_GT(ceiling_hits, 50);
}

// A wall at x = 2 with a door at |y| <= 0.6 and jambs 0.2 m deep. A ray that slips through
// the opening near its edge at a slant is stopped by the jamb; without jambs it goes through.
TEST(RayCaster, DoorFrameOccludes) {
  OfficeParams office;
  office.rooms = {2, 1};
  office.room_size = {4.0, 6.0};  // the wall between the rooms lies on x = 2, the door at y = 0
  office.door_width = 1.2;
  office.frame_depth = 0.2;
  const Eigen::Vector3d origin(0.0, -1.5, 1.0);
  // Crosses x = 2 at y = 0.55 (inside the opening), then meets the jamb face y = 0.6.
  const Eigen::Vector3d direction = Eigen::Vector3d(2.0, 2.05, 0.0).normalized();
  const double expected =
      (Eigen::Vector2d(2.0 + 0.05 / 1.025, 0.6) - Eigen::Vector2d(0, -1.5)).norm();

  World with_frame;
  AddOffice(office, 2.5, &with_frame.rects);
  const Hit hit = RayCaster(with_frame).CastOneBruteForce(origin, direction, 50.0);
  ASSERT_GE(hit.rect, 0);
  EXPECT_NEAR(hit.range, expected, 1e-9);
  const Eigen::Vector3d n = with_frame.rects[hit.rect].Normal();
  EXPECT_NEAR(std::abs(n.y()), 1.0, 1e-12) << "the jamb runs across the wall, facing +-y";

  office.frame_depth = 0.0;
  World without_frame;
  AddOffice(office, 2.5, &without_frame.rects);
  const Hit through = RayCaster(without_frame).CastOneBruteForce(origin, direction, 50.0);
  ASSERT_GE(through.rect, 0);
  EXPECT_GT(through.range, expected + 1.0) << "without a frame the ray passes into room 2";
}

// The column index must return exactly what brute force returns: same rectangle, same range
// bit for bit, for every ray, in a cluttered world with walls of all heights and tilted
// rectangles.
TEST(RayCaster, IndexEqualsBruteForceOnRandomWorld) {
  World world;
  AddRandomClutter(150, 12, 24.0, 42, &world.rects);
  world.rects.push_back(Rect{{-12, -12, 0}, {24, 0, 0}, {0, 24, 0}});    // floor
  world.rects.push_back(Rect{{-12, -12, 2.5}, {0, 24, 0}, {24, 0, 0}});  // ceiling
  RayCaster caster(world);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-10.0, 10.0);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  int tilted_hits = 0;
  int wall_hits = 0;
  int misses = 0;
  for (const auto& [hfov, vfov] : {std::pair{90.0, 60.0}, std::pair{160.0, 150.0}}) {
    const RayGrid grid = RayGrid::Pinhole(64, 48, hfov * kDeg, vfov * kDeg);
    for (int trial = 0; trial < 20; ++trial) {
      const Eigen::Vector3d origin(pos(rng), pos(rng), 1.0);
      const double yaw = angle(rng);
      std::vector<Hit> fast;
      std::vector<Hit> slow;
      caster.Cast(origin, yaw, grid, 8.0, &fast);
      caster.CastBruteForce(origin, yaw, grid, 8.0, &slow);
      ASSERT_EQ(fast.size(), slow.size());
      for (size_t i = 0; i < fast.size(); ++i) {
        ASSERT_EQ(fast[i].rect, slow[i].rect) << "trial " << trial << " ray " << i;
        ASSERT_EQ(fast[i].range, slow[i].range) << "trial " << trial << " ray " << i;
        if (slow[i].rect < 0) {
          ++misses;
        } else if (slow[i].rect >= 150 && slow[i].rect < 162) {
          ++tilted_hits;
        } else if (slow[i].rect < 150) {
          ++wall_hits;
        }
      }
    }
  }
  // The comparison covered every kind of outcome.
  EXPECT_GT(wall_hits, 10000);
  EXPECT_GT(tilted_hits, 100);
  EXPECT_GT(misses, 100);
}

}  // namespace
}  // namespace relplane::sim
