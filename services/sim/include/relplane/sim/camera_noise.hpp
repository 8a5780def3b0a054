#pragma once
// A depth camera's measurement of one pixel under a camera model (relplane/common/
// depth_camera.hpp): lateral noise, axial noise, quantization and the cases with no return.

#include <Eigen/Core>
#include <optional>

#include "relplane/common/depth_camera.hpp"

namespace relplane::sim {

// Standard normal draws for one pixel, drawn by the caller so a frame stays a function of
// (seed, frame).
struct CameraDraws {
  double axial = 0.0;
  double lateral_u = 0.0;
  double lateral_v = 0.0;
};

// The point the camera reports for the pixel whose unit ray is `ray` (sensor frame, ray.x() >
// 0), whose true surface is the plane normal . p + d = 0 (sensor frame): the surface's depth
// at the pixel displaced by the lateral noise, plus the axial noise, on the camera's lattice,
// placed on the pixel's own ray. nullopt when the camera returns nothing there (grazing
// incidence, nearer than min_depth or beyond max_depth).
std::optional<Eigen::Vector3d> MeasurePixel(const camera::DepthCameraModel& model,
                                            const Eigen::Vector3d& ray,
                                            const Eigen::Vector3d& normal, double d,
                                            const CameraDraws& draws);

}  // namespace relplane::sim
