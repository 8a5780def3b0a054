#pragma once
// The simulated world: a list of rectangles (walls with a height, floor, ceiling, anything
// else) in the world frame, z up. Built from literal lists and generators (generators.hpp).

#include <Eigen/Geometry>
#include <string>
#include <variant>
#include <vector>

#include "relplane/sim/generators.hpp"
#include "relplane/sim/random_indoor.hpp"

namespace relplane::sim {

// A rectangle: corners origin, origin + u, origin + u + v, origin + v (in that order around
// it). u and v must be perpendicular and non-zero.
struct Rect {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();

  // Unit normal u x v; the plane is normal . p + d = 0.
  Eigen::Vector3d Normal() const { return u.cross(v).normalized(); }
  double D() const { return -Normal().dot(origin); }
  Eigen::Vector3d Centroid() const { return origin + 0.5 * (u + v); }
  // The four corners in order around the rectangle.
  std::vector<Eigen::Vector3d> Corners() const {
    return {origin, origin + u, origin + u + v, origin + v};
  }
  // A vertical wall over the floor-plan segment a -> b, from z = base to z = base + height.
  static Rect Wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double base, double height);
};

// A wall given by its floor-plan segment; height < 0 means the world's height.
struct WallSpec {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::UnitX();
  double base = 0.0;
  double height = -1.0;
};

using GeneratorSpec =
    std::variant<StraightHallwayParams, HallwayLoopParams, OfficeParams, RandomIndoorParams>;

struct WorldOptions {
  double height = 2.5;  // wall height and ceiling height, metres
  bool floor = true;    // a floor rectangle at z = 0 under the walls' bounding box
  bool ceiling = true;  // a ceiling rectangle at z = height over the same box
  std::vector<GeneratorSpec> generators = {StraightHallwayParams{}};
  std::vector<WallSpec> walls;
  std::vector<Rect> rectangles;
};

struct World {
  std::vector<Rect> rects;
};

// Generated walls first (in generator order), then literal walls, then literal rectangles,
// then floor and ceiling. Floor and ceiling are left out when there is no wall to bound them.
World BuildWorld(const WorldOptions& options);

// Number of walls (rectangles whose normal is horizontal) in `world`.
int CountWalls(const World& world);

}  // namespace relplane::sim
