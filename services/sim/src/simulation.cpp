#include "relplane/sim/simulation.hpp"

#include <cmath>

namespace relplane::sim {

std::vector<TruePlane> TruePlanes(const World& world) {
  std::vector<TruePlane> planes;
  planes.reserve(world.rects.size());
  for (size_t i = 0; i < world.rects.size(); ++i) {
    const Rect& r = world.rects[i];
    TruePlane p;
    p.id = static_cast<int>(i);
    p.normal = r.Normal();
    p.d = r.D();
    p.centroid = r.Centroid();
    const std::vector<Eigen::Vector3d> corners = r.Corners();
    for (int c = 0; c < 4; ++c) p.corners[c] = corners[c];
    planes.push_back(p);
  }
  return planes;
}

Simulation::Simulation(const SimOptions& options)
    : options_(options),
      world_(BuildWorld(options.world)),
      trajectory_(options.trajectory),
      sensor_(world_, options.sensor),
      num_iterations_(trajectory_.NumSamples(1.0 / options.rate_hz)) {}

int64_t Simulation::Utime(int64_t k) const {
  return std::llround(static_cast<double>(k) * 1e6 / options_.rate_hz);
}

geometry::Pose2 Simulation::PlanarPose(int64_t k) const {
  return trajectory_.Sample(k, 1.0 / options_.rate_hz);
}

Eigen::Isometry3d Simulation::SensorPose(int64_t k) const {
  return geometry::ToIsometry(PlanarPose(k), options_.sensor.mount_height);
}

Scan Simulation::Frame(int64_t k) {
  return sensor_.Capture(PlanarPose(k), static_cast<uint64_t>(k));
}

}  // namespace relplane::sim
