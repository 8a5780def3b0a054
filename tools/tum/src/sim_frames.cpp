#include "relplane/tum/sim_frames.hpp"

#include <cmath>

namespace relplane::tum {

namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
}  // namespace

Intrinsics SimIntrinsics(const sim::SensorOptions& sensor, double depth_scale) {
  // RayGrid::Pinhole: column c looks along y = tan(hfov / 2) (1 - (2c + 1) / width) at unit
  // depth, which is -(c - cx) / fx with fx = width / (2 tan(hfov / 2)), cx = (width - 1) / 2.
  Intrinsics k;
  k.fx = sensor.width / (2.0 * std::tan(0.5 * sensor.hfov_deg * kDegToRad));
  k.fy = sensor.height / (2.0 * std::tan(0.5 * sensor.vfov_deg * kDegToRad));
  k.cx = 0.5 * (sensor.width - 1);
  k.cy = 0.5 * (sensor.height - 1);
  k.depth_scale = depth_scale;
  return k;
}

DepthImage ScanToDepthImage(const sim::Scan& scan, const sim::SensorOptions& sensor,
                            double depth_scale, int* clipped) {
  DepthImage image;
  image.width = sensor.width;
  image.height = sensor.height;
  image.values.assign(static_cast<size_t>(sensor.width) * sensor.height, 0);
  int over = 0;
  for (size_t i = 0; i < scan.points.size() && i < scan.pixels.size(); ++i) {
    // The grid's index is column-major: col * height + row.
    const int col = scan.pixels[i] / sensor.height;
    const int row = scan.pixels[i] % sensor.height;
    const double value = std::round(scan.points[i].x() * depth_scale);
    if (!(value >= 1.0 && value <= 65535.0)) {
      ++over;
      continue;
    }
    image.values[static_cast<size_t>(row) * sensor.width + col] = static_cast<uint16_t>(value);
  }
  if (clipped != nullptr) *clipped = over;
  return image;
}

}  // namespace relplane::tum
