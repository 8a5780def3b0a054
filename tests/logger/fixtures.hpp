#pragma once
// Hand-made worlds, maps and trajectories with known answers for the evaluation tests.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "relplane/eval/types.hpp"

namespace relplane::testing {

// A vertical wall from a to b (x-y), 0 to 2.5 m high, normal to the left of a -> b.
inline eval::PlaneRecord Wall(int64_t id, Eigen::Vector2d a, Eigen::Vector2d b) {
  eval::PlaneRecord p;
  p.id = id;
  const Eigen::Vector2d dir = (b - a).normalized();
  p.normal = Eigen::Vector3d(-dir.y(), dir.x(), 0.0);
  p.d = -p.normal.head<2>().dot(a);
  p.vertices = {{a.x(), a.y(), 0.0}, {b.x(), b.y(), 0.0}, {b.x(), b.y(), 2.5}, {a.x(), a.y(), 2.5}};
  p.centroid = Eigen::Vector3d(0.5 * (a.x() + b.x()), 0.5 * (a.y() + b.y()), 1.25);
  p.observations = 10;
  return p;
}

// A horizontal plane (floor) that the map metrics must ignore.
inline eval::PlaneRecord Floor(int64_t id) {
  eval::PlaneRecord p;
  p.id = id;
  p.normal = Eigen::Vector3d::UnitZ();
  p.vertices = {{-1, -2, 0}, {5, -2, 0}, {5, 2, 0}, {-1, 2, 0}};
  return p;
}

// A 6 m x 4 m room, x in [-1, 5], y in [-2, 2]; walls 0..3 counter-clockwise from the south.
inline eval::MapSnapshot Room() {
  eval::MapSnapshot world;
  world.planes = {Wall(0, {-1, -2}, {5, -2}), Wall(1, {5, -2}, {5, 2}), Wall(2, {5, 2}, {-1, 2}),
                  Wall(3, {-1, 2}, {-1, -2}), Floor(4)};
  return world;
}

inline eval::PoseSample Pose(int64_t seq, double x, double y, double yaw, int status = 1) {
  eval::PoseSample p;
  p.seq = seq;
  p.utime = seq * 100000;  // 10 Hz
  p.position = {x, y, 1.0};
  p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  p.status = status;
  return p;
}

// A loop inside the room: out along +x, a half turn, back, another half turn (seen all walls).
inline std::vector<eval::PoseSample> LoopInRoom() {
  std::vector<eval::PoseSample> poses;
  int64_t seq = 0;
  for (int i = 0; i <= 40; ++i) poses.push_back(Pose(seq++, 0.1 * i, -0.5, 0.0));
  for (int i = 1; i <= 18; ++i) poses.push_back(Pose(seq++, 4.0, -0.5 + i / 18.0, M_PI * i / 18.0));
  for (int i = 1; i <= 40; ++i) poses.push_back(Pose(seq++, 4.0 - 0.1 * i, 0.5, M_PI));
  for (int i = 1; i <= 18; ++i) {
    poses.push_back(Pose(seq++, 0.0, 0.5 - i / 18.0, M_PI + M_PI * i / 18.0));
  }
  return poses;
}

}  // namespace relplane::testing
