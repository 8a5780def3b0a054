#include "relplane/sim/depth_sensor.hpp"

#include <cmath>
#include <random>

#include "relplane/sim/camera_noise.hpp"

namespace relplane::sim {

namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
}  // namespace

DepthSensor::DepthSensor(const World& world, const SensorOptions& options)
    : options_(options),
      grid_(RayGrid::Pinhole(options.width, options.height, options.hfov_deg * kDegToRad,
                             options.vfov_deg * kDegToRad)),
      caster_(world) {
  for (const Rect& r : world.rects) {
    const Eigen::Vector3d n = r.Normal();
    planes_.emplace_back(n.x(), n.y(), n.z(), r.D());
  }
}

const std::vector<Hit>& DepthSensor::CastTrue(const geometry::Pose2& pose) {
  caster_.Cast(Eigen::Vector3d(pose.x, pose.y, options_.mount_height), pose.yaw, grid_,
               options_.max_range, &hits_);
  return hits_;
}

Scan DepthSensor::Capture(const geometry::Pose2& pose, uint64_t frame) {
  if (options_.camera.name != "gaussian") return CaptureWithCamera(pose, frame);
  CastTrue(pose);
  // One generator per frame, seeded from (seed, frame), so a frame does not depend on which
  // frames were captured before it. The golden-ratio constant spreads neighbouring frames.
  std::mt19937_64 rng(options_.seed ^ (0x9E3779B97F4A7C15ULL * (frame + 1)));
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  // A perfect sensor skips the draws, which cost more than the ray casting.
  const bool perfect = options_.noise_sigma == 0.0 && options_.dropout == 0.0;

  Scan scan;
  scan.points.reserve(hits_.size());
  scan.rects.reserve(hits_.size());
  scan.pixels.reserve(hits_.size());
  for (size_t i = 0; i < hits_.size(); ++i) {
    const Hit& hit = hits_[i];
    if (hit.rect < 0) continue;
    double range = hit.range;
    if (!perfect) {
      // Both draws happen for every hit, so the dropout rate does not change the noise.
      const double drop = uniform(rng);
      range += options_.noise_sigma * noise(rng);
      if (drop < options_.dropout || range <= 0.0) continue;
    }
    scan.points.push_back((range * grid_.directions[i]).cast<float>());
    scan.rects.push_back(hit.rect);
    scan.pixels.push_back(static_cast<int>(i));
  }
  return scan;
}

Scan DepthSensor::CaptureWithCamera(const geometry::Pose2& pose, uint64_t frame) {
  CastTrue(pose);
  std::mt19937_64 rng(options_.seed ^ (0x9E3779B97F4A7C15ULL * (frame + 1)));
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  // The rectangles' planes in the sensor frame: p_world = R p + o, so n_s = R^T n, d_s = n.o + d.
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  const Eigen::Vector3d origin(pose.x, pose.y, options_.mount_height);
  Scan scan;
  scan.points.reserve(hits_.size());
  scan.rects.reserve(hits_.size());
  scan.pixels.reserve(hits_.size());
  for (size_t i = 0; i < hits_.size(); ++i) {
    const Hit& hit = hits_[i];
    if (hit.rect < 0) continue;
    // Every draw happens for every hit, so one pixel's fate does not change another's noise.
    const double drop = uniform(rng);
    CameraDraws draws;
    draws.axial = noise(rng);
    draws.lateral_u = noise(rng);
    draws.lateral_v = noise(rng);
    if (drop < options_.dropout) continue;
    const Eigen::Vector4d& w = planes_[static_cast<size_t>(hit.rect)];
    const Eigen::Vector3d normal(c * w.x() + s * w.y(), -s * w.x() + c * w.y(), w.z());
    const double d = w.head<3>().dot(origin) + w.w();
    const auto point = MeasurePixel(options_.camera, grid_.directions[i], normal, d, draws);
    if (!point) continue;
    scan.points.push_back(point->cast<float>());
    scan.rects.push_back(hit.rect);
    scan.pixels.push_back(static_cast<int>(i));
  }
  return scan;
}

}  // namespace relplane::sim
