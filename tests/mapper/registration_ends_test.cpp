// Registration (§II.A) and static edges (§II.C): an end seen uncut far from where the same
// rltplane's end last was is another end (a door wall seen whole, then in pieces) and is marked
// cut; an end that moves with the sensor is not.
#include <gtest/gtest.h>

#include <vector>

#include "plane_store/registration.hpp"
#include "state_parts.hpp"

namespace relplane::mapper {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// The wall from p0 to p1 as the segmenter reports it from a sensor at the origin facing +x.
Observation Seen(Vector2d p0, Vector2d p1, int64_t iteration) {
  PlaneInput in;
  Vector2d n(-(p1 - p0).y(), (p1 - p0).x());
  n.normalize();
  if (n.dot(p0) > 0) n = -n;
  in.normal = Vector3d(n.x(), n.y(), 0);
  in.d = -n.dot(p0);
  in.centroid = Vector3d(0.5 * (p0 + p1).x(), 0.5 * (p0 + p1).y(), 0);
  in.vertices = {
      {p0.x(), p0.y(), -1}, {p1.x(), p1.y(), -1}, {p1.x(), p1.y(), 1}, {p0.x(), p0.y(), 1}};
  return *MakeObservation(in, iteration, 0.3);
}

// The end of `obs` nearest `p`.
int EndAt(const Observation& obs, const Vector2d& p) {
  return (obs.edge[0] - p).norm() < (obs.edge[1] - p).norm() ? 0 : 1;
}

TEST(MarkJumpedEnds, APieceOfAWallSeenWholeHasItsDoorSideEndCut) {
  // A 4 m wall 3 m ahead, seen whole (both corners in view) from a standing sensor for 20
  // iterations; then a door in it opens the view and the wall is seen as two pieces.
  MapperState state;
  RltPlane wall(0, Seen({3, -2}, {3, 2}, 0), 0.05, 3000);
  state.trajectory.poses[0] = {0, 0, 0};
  for (int64_t k = 1; k < 20; ++k) {
    wall.Add(Seen({3, -2}, {3, 2}, k));
    state.trajectory.poses[k] = {0, 0, 0};
  }
  state.store.planes.emplace(0, wall);
  std::vector<Observation> now = {Seen({3, -2}, {3, -0.6}, 20), Seen({3, 0.6}, {3, 2}, 20)};
  MarkJumpedEnds({0, -1}, state.store, state.trajectory, {0, 0, 0}, &now);
  // The piece continuing the wall keeps its corner and has its door-side end cut.
  EXPECT_FALSE(now[0].cut[EndAt(now[0], {3, -2})]);
  EXPECT_TRUE(now[0].cut[EndAt(now[0], {3, -0.6})]);
  // The other piece becomes a new rltplane: nothing to compare with, nothing marked.
  EXPECT_FALSE(now[1].cut[0]);
  EXPECT_FALSE(now[1].cut[1]);
}

TEST(MarkJumpedEnds, AnEndThatMovesWithTheSensorIsNotCut) {
  // The sensor drives along a 6 m side wall at 1 m/s, 30 Hz: in its frame the wall's far end
  // comes 3.3 cm closer every iteration, on the map it stays.
  MapperState state;
  const auto seen_from = [](double x, int64_t k) {
    return Seen(Vector2d(-x, 1.0), Vector2d(6.0 - x, 1.0), k);
  };
  RltPlane wall(0, seen_from(0.0, 0), 0.05, 3000);
  state.trajectory.poses[0] = {0, 0, 0};
  for (int64_t k = 1; k < 30; ++k) {
    wall.Add(seen_from(k / 30.0, k));
    state.trajectory.poses[k] = {k / 30.0, 0, 0};
  }
  state.store.planes.emplace(0, wall);
  std::vector<Observation> now = {seen_from(1.0, 30)};
  MarkJumpedEnds({0}, state.store, state.trajectory, state.trajectory.poses.rbegin()->second, &now);
  EXPECT_FALSE(now[0].cut[0]);
  EXPECT_FALSE(now[0].cut[1]);
}

}  // namespace
}  // namespace relplane::mapper
