#include "relplane/sim/world.hpp"

#include <cmath>
#include <limits>

namespace relplane::sim {

Rect Rect::Wall(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double base, double height) {
  Rect r;
  r.origin = Eigen::Vector3d(a.x(), a.y(), base);
  r.u = Eigen::Vector3d(b.x() - a.x(), b.y() - a.y(), 0.0);
  r.v = Eigen::Vector3d(0.0, 0.0, height);
  return r;
}

namespace {

struct GeneratorVisitor {
  double height;
  std::vector<Rect>* out;
  void operator()(const StraightHallwayParams& p) const { AddStraightHallway(p, height, out); }
  void operator()(const HallwayLoopParams& p) const { AddHallwayLoop(p, height, out); }
  void operator()(const OfficeParams& p) const { AddOffice(p, height, out); }
  void operator()(const RandomIndoorParams& p) const {
    for (const auto& [from, to] : MakeRandomIndoor(p).walls) {
      out->push_back(Rect::Wall(from, to, 0.0, height));
    }
  }
};

bool IsWall(const Rect& r) { return std::abs(r.Normal().z()) < 0.1; }

}  // namespace

World BuildWorld(const WorldOptions& options) {
  World world;
  for (const GeneratorSpec& g : options.generators) {
    std::visit(GeneratorVisitor{options.height, &world.rects}, g);
  }
  for (const WallSpec& w : options.walls) {
    const double height = w.height < 0.0 ? options.height : w.height;
    world.rects.push_back(Rect::Wall(w.from, w.to, w.base, height));
  }
  world.rects.insert(world.rects.end(), options.rectangles.begin(), options.rectangles.end());

  // Floor and ceiling cover the bounding box of the walls' footprints.
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  bool any_wall = false;
  for (const Rect& r : world.rects) {
    if (!IsWall(r)) continue;
    any_wall = true;
    for (const Eigen::Vector3d& c : r.Corners()) {
      lo = lo.cwiseMin(c.head<2>());
      hi = hi.cwiseMax(c.head<2>());
    }
  }
  if (!any_wall || (hi - lo).minCoeff() <= 0.0) return world;
  const Eigen::Vector3d dx(hi.x() - lo.x(), 0.0, 0.0);
  const Eigen::Vector3d dy(0.0, hi.y() - lo.y(), 0.0);
  if (options.floor) {
    // u x v = +z: the floor's normal points up, into the room.
    world.rects.push_back(Rect{Eigen::Vector3d(lo.x(), lo.y(), 0.0), dx, dy});
  }
  if (options.ceiling) {
    world.rects.push_back(Rect{Eigen::Vector3d(lo.x(), lo.y(), options.height), dy, dx});
  }
  return world;
}

int CountWalls(const World& world) {
  int n = 0;
  for (const Rect& r : world.rects) n += IsWall(r) ? 1 : 0;
  return n;
}

}  // namespace relplane::sim
