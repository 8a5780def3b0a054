#pragma once
// A depth sensor: a grid of rays cast into the world, range noise along each ray and random
// dropouts, reproducible from a fixed seed and the frame number.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "relplane/common/depth_camera.hpp"
#include "relplane/common/geometry.hpp"
#include "relplane/sim/ray_caster.hpp"
#include "relplane/sim/world.hpp"

namespace relplane::sim {

struct SensorOptions {
  int width = 160;            // rays per row
  int height = 120;           // rows
  double hfov_deg = 90.0;     // horizontal field of view, degrees (< 180)
  double vfov_deg = 60.0;     // vertical field of view, degrees (< 180)
  double max_range = 8.0;     // metres along the ray; nothing further is returned
  double mount_height = 1.0;  // sensor height above the floor (z = 0), metres
  double noise_sigma = 0.0;   // standard deviation of Gaussian range noise along the ray, metres
  double dropout = 0.0;       // probability that a hit is lost, in [0, 1)
  uint64_t seed = 1;          // noise and dropout are a function of (seed, frame)
  // The camera model: "gaussian" (noise_sigma along the ray, nothing else) or a named camera
  // (relplane/common/depth_camera.hpp) whose noise, quantization and limits replace it.
  camera::DepthCameraModel camera;
};

// One frame: points in the sensor frame (x forward, y left, z up), only hits, in the grid's
// order (column by column, left to right), and for each point the index of the rectangle it
// came from.
struct Scan {
  std::vector<Eigen::Vector3f> points;
  std::vector<int> rects;
  std::vector<int> pixels;  // per point: its ray's index in the grid (col * height + row)
};

class DepthSensor {
 public:
  DepthSensor(const World& world, const SensorOptions& options);

  // The noise-free nearest hit of every ray from `pose` (the sensor at mount height), in the
  // grid's order (column by column).
  const std::vector<Hit>& CastTrue(const geometry::Pose2& pose);
  // A frame as the sensor reports it: hits with range noise, minus dropouts. The same
  // (pose, frame) always gives the same scan.
  Scan Capture(const geometry::Pose2& pose, uint64_t frame);

  const RayGrid& Grid() const { return grid_; }
  const SensorOptions& Options() const { return options_; }

 private:
  // A camera model's frame (options_.camera other than "gaussian").
  Scan CaptureWithCamera(const geometry::Pose2& pose, uint64_t frame);

  SensorOptions options_;
  std::vector<Eigen::Vector4d> planes_;  // per rectangle: world normal and offset
  RayGrid grid_;
  RayCaster caster_;
  std::vector<Hit> hits_;
};

}  // namespace relplane::sim
