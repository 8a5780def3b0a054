// Generated indoor worlds: valid by construction (the route keeps clear of every wall, the
// walls are closed boundaries), varied, and fixed by the seed.
#include "relplane/sim/random_indoor.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "relplane/common/geometry.hpp"
#include "relplane/sim/trajectory.hpp"
#include "relplane/sim/world.hpp"

namespace relplane::sim {
namespace {

double Clearance(const IndoorLayout& layout) {
  double closest = 1e9;
  const size_t legs = layout.route.size() - 1 + (layout.closed ? 1 : 0);
  for (size_t k = 0; k < legs; ++k) {
    const Eigen::Vector2d a = layout.route[k];
    const Eigen::Vector2d b = layout.route[(k + 1) % layout.route.size()];
    for (int s = 0; s <= 200; ++s) {
      const Eigen::Vector2d p = a + (b - a) * (s / 200.0);
      for (const auto& [from, to] : layout.walls) {
        closest = std::min(closest, geometry::Segment2{from, to}.DistanceTo(p));
      }
    }
  }
  return closest;
}

TEST(RandomIndoor, RoutesKeepClearOfEveryWallOnManySeeds) {
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE(seed);
    const IndoorLayout layout = MakeRandomIndoor({seed});
    ASSERT_GE(layout.route.size(), 3u);
    EXPECT_EQ(layout.route[0], Eigen::Vector2d::Zero());
    EXPECT_GE(Clearance(layout), kRouteClearance - 1e-9) << layout.description;
    // The route drives: a trajectory accepts it.
    TrajectoryOptions t;
    t.waypoints = layout.route;
    t.closed = layout.closed;
    t.laps = layout.laps;
    t.drive_back = layout.drive_back;
    EXPECT_NO_THROW(Trajectory{t});
  }
}

TEST(RandomIndoor, WallsCloseTheFreeSpace) {
  // Every wall end is shared by another wall's end: the boundary has no gap a ray could leave by.
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const IndoorLayout layout = MakeRandomIndoor({seed});
    std::map<std::pair<long, long>, int> ends;
    for (const auto& [from, to] : layout.walls) {
      EXPECT_GT((to - from).norm(), 0.2);
      for (const Eigen::Vector2d& p : {from, to}) {
        ++ends[{std::lround(p.x() * 8), std::lround(p.y() * 8)}];
      }
    }
    for (const auto& [point, count] : ends) EXPECT_EQ(count % 2, 0) << "seed " << seed;
  }
}

TEST(RandomIndoor, SeedsGiveVariedWorldsAndTheSameSeedTheSameWorld) {
  std::set<std::string> routes;
  int loops = 0, out_and_back = 0, twice = 0, with_pillars = 0, with_doorways = 0, recesses = 0;
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    const IndoorLayout layout = MakeRandomIndoor({seed});
    routes.insert(layout.description);
    loops += layout.closed ? 1 : 0;
    out_and_back += layout.drive_back ? 1 : 0;
    twice += layout.laps == 2 ? 1 : 0;
    with_pillars += layout.description.find(" 0 pillars") == std::string::npos ? 1 : 0;
    with_doorways += layout.description.find(" 0 doorways") == std::string::npos ? 1 : 0;
    recesses += layout.description.find(" 0 recesses") == std::string::npos ? 1 : 0;
  }
  EXPECT_GT(routes.size(), 30u);
  EXPECT_GT(loops, 5);
  EXPECT_GT(out_and_back, 5);
  EXPECT_GT(twice, 1);
  EXPECT_GT(with_pillars, 5);
  EXPECT_GT(with_doorways, 5);
  EXPECT_GT(recesses, 5);
  const IndoorLayout a = MakeRandomIndoor({17}), b = MakeRandomIndoor({17});
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (size_t k = 0; k < a.walls.size(); ++k) EXPECT_EQ(a.walls[k].first, b.walls[k].first);
}

TEST(RandomIndoor, WorldHasTheLayoutsWallsAtFullHeight) {
  WorldOptions options;
  options.height = 2.5;
  options.generators = {RandomIndoorParams{5}};
  const World world = BuildWorld(options);
  EXPECT_EQ(CountWalls(world), static_cast<int>(MakeRandomIndoor({5}).walls.size()));
  for (const Rect& r : world.rects) {
    if (std::abs(r.Normal().z()) > 0.1) continue;
    EXPECT_DOUBLE_EQ(r.origin.z(), 0.0);
    EXPECT_DOUBLE_EQ(r.v.z(), 2.5);
  }
}

}  // namespace
}  // namespace relplane::sim
