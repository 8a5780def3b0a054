#include "relplane/sim/camera_noise.hpp"

#include <cmath>

namespace relplane::sim {

namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
}  // namespace

std::optional<Eigen::Vector3d> MeasurePixel(const camera::DepthCameraModel& model,
                                            const Eigen::Vector3d& ray,
                                            const Eigen::Vector3d& normal, double d,
                                            const CameraDraws& draws) {
  if (std::abs(normal.dot(ray)) < std::cos(model.max_incidence_deg * kDegToRad)) {
    return std::nullopt;
  }
  // The pixel's ray scaled to unit depth: depth z puts the point at z * pixel.
  const Eigen::Vector3d pixel = ray / ray.x();
  const double facing = normal.dot(pixel);
  double z = -d / facing;
  if (model.lateral_px > 0.0) {
    // The depth measured at a pixel is the surface's at a neighbouring one (the camera matches
    // or integrates over a window): the same surface, along a ray displaced in the image.
    const double scale = model.lateral_px / model.focal_px;
    const Eigen::Vector3d shifted =
        pixel + Eigen::Vector3d(0.0, draws.lateral_u * scale, draws.lateral_v * scale);
    const double shifted_facing = normal.dot(shifted);
    // A displaced ray that leaves the surface's side keeps the pixel's own depth.
    if (shifted_facing * facing > 0.0) z = -d / shifted_facing;
  }
  z += model.AxialSigma(z) * draws.axial;
  z = model.Quantize(z);
  if (!(z >= model.min_depth && z <= model.max_depth && z > 0.0)) return std::nullopt;
  return z * pixel;
}

}  // namespace relplane::sim
