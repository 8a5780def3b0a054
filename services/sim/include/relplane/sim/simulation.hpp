#pragma once
// The whole simulation of one scenario: world, trajectory and sensor, stepped by iteration, as
// the paper's tests do (§III: a simulated 3D point field seen by a moving sensor, Figs. 5-8).
// Iteration k is simulated time k / rate_hz; nothing here reads a clock.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "relplane/sim/depth_sensor.hpp"
#include "relplane/sim/trajectory.hpp"
#include "relplane/sim/world.hpp"

namespace relplane::sim {

struct SimOptions {
  double rate_hz = 30.0;  // iterations per simulated second; dt = 1 / rate_hz
  WorldOptions world;
  TrajectoryOptions trajectory;
  SensorOptions sensor;
};

// One true rectangle as SIM_WORLD describes it (DESIGN.md "Scenario conventions").
struct TruePlane {
  int id = 0;  // index in the world
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0.0;  // normal . p + d = 0
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::array<Eigen::Vector3d, 4> corners;  // in order around the rectangle
};

std::vector<TruePlane> TruePlanes(const World& world);

class Simulation {
 public:
  // Throws std::invalid_argument when the trajectory cannot be built.
  explicit Simulation(const SimOptions& options);

  int64_t NumIterations() const { return num_iterations_; }
  // Simulated capture time of iteration k in microseconds: k * 1e6 / rate_hz.
  int64_t Utime(int64_t k) const;
  // The sensor's floor-plan pose at iteration k, and at simulated time t seconds.
  geometry::Pose2 PlanarPose(int64_t k) const;
  geometry::Pose2 PlanarPoseAt(double t) const { return trajectory_.At(t); }
  // The true sensor pose at iteration k: world <- sensor, at the mount height.
  Eigen::Isometry3d SensorPose(int64_t k) const;
  // The frame captured at iteration k.
  Scan Frame(int64_t k);

  const World& GetWorld() const { return world_; }
  std::vector<TruePlane> TruePlanes() const { return sim::TruePlanes(world_); }
  const SimOptions& Options() const { return options_; }

 private:
  SimOptions options_;
  World world_;
  Trajectory trajectory_;
  DepthSensor sensor_;
  int64_t num_iterations_;
};

}  // namespace relplane::sim
