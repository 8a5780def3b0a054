// World kinds from the true poses: what the walls in view fix, frame by frame.
#include "relplane/accuracy/world_kind.hpp"

#include <gtest/gtest.h>

namespace relplane::accuracy {
namespace {

sim::SimOptions Drive(std::vector<sim::WallSpec> walls, std::vector<Eigen::Vector2d> route) {
  sim::SimOptions o;
  o.world.generators.clear();
  o.world.walls = std::move(walls);
  o.trajectory.waypoints = std::move(route);
  o.trajectory.speed = 1.0;
  return o;
}

sim::WallSpec Wall(double x0, double y0, double x1, double y1) {
  sim::WallSpec w;
  w.from = {x0, y0};
  w.to = {x1, y1};
  return w;
}

TEST(WorldKind, AClosedRoomIsObservableThroughout) {
  // 6 m x 4 m, driven 3 m along its middle: a corner or an end wall is always in view.
  const sim::Simulation sim(Drive({Wall(-1, -2, 5, -2), Wall(5, -2, 5, 2), Wall(5, 2, -1, 2),
                                   Wall(-1, 2, -1, -2)},
                                  {{0, 0}, {3, 0}}));
  const WorldKind kind = ClassifyWorld(sim);
  EXPECT_EQ(kind.frames, sim.NumIterations());
  EXPECT_TRUE(kind.Observable()) << kind.unobservable_frames << " frames open";
  EXPECT_EQ(kind.Label(), "observable");
}

TEST(WorldKind, ALongPlainCorridorLeavesItsAxisOpen) {
  // 30 m long, 2 m wide, closed far beyond the 8 m range: the first 10 m show only two parallel
  // walls, their near ends behind the sensor.
  const sim::Simulation sim(Drive({Wall(-5, -1, 25, -1), Wall(25, 1, -5, 1), Wall(25, -1, 25, 1),
                                   Wall(-5, 1, -5, -1)},
                                  {{0, 0}, {10, 0}}));
  const WorldKind kind = ClassifyWorld(sim);
  EXPECT_FALSE(kind.Observable());
  EXPECT_GT(kind.longest_stretch_s, 5.0);
  EXPECT_EQ(kind.Label(), "unobservable >= 1 s");
  EXPECT_EQ(static_cast<int64_t>(kind.unobservable.size()), kind.unobservable_frames);
}

}  // namespace
}  // namespace relplane::accuracy
