#include "published_map/published_map.hpp"

#include <utility>

#include "global_map/global_map.hpp"
#include "published_map/map_cleanup.hpp"

namespace relplane::mapper {

MapSnapshot PublishedMap(const MapperState& state, const MapperOptions& options) {
  const double height = options.start_pose.z;  // planes are mapped at sensor z + this
  MapSnapshot snapshot;
  for (const auto& [id, placed] : state.world.global) {
    const RltPlane& plane = state.store.planes.at(id);
    if (placed.known == Known::kAngle) continue;
    const Eigen::Vector2d n = NormalOf(placed.alpha);
    Eigen::Vector2d lo, hi;
    WallEnds(state.trajectory, plane, placed, &lo, &hi);
    const double z0 = plane.ZMin() + height, z1 = plane.ZMax() + height;
    MappedPlane m;
    m.id = id;
    m.normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
    m.d = -n.dot(placed.point);
    m.vertices = {
        {lo.x(), lo.y(), z0}, {hi.x(), hi.y(), z0}, {hi.x(), hi.y(), z1}, {lo.x(), lo.y(), z1}};
    const Eigen::Vector2d mid = 0.5 * (lo + hi);
    m.centroid = Eigen::Vector3d(mid.x(), mid.y(), 0.5 * (z0 + z1));
    m.observations = plane.Count();
    m.both_ends_known =
        placed.known == Known::kPoint && (placed.has_other || plane.FullLengthKnown());
    m.end_known[0] = placed.known == Known::kPoint && (placed.ref == 0 || m.both_ends_known);
    m.end_known[1] = placed.known == Known::kPoint && (placed.ref == 1 || m.both_ends_known);
    snapshot.planes.push_back(std::move(m));
  }
  CleanUpWalls(&snapshot.planes, options.published_map, options.fit);  // §II.D end
  for (const Group& g : state.grouping.groups) {
    snapshot.groups.push_back({g.id, g.relative.basis, g.members});
  }
  return snapshot;
}

}  // namespace relplane::mapper
