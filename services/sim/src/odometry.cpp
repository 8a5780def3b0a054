#include "relplane/sim/odometry.hpp"

#include <cmath>

namespace relplane::sim {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

}  // namespace

WheelOdometry::WheelOdometry(const OdometryOptions& options, const geometry::Pose2& start)
    : options_(options),
      rng_(options.seed ^ 0x0D0E7E1ULL),
      previous_true_(start),
      odometry_(start) {}

geometry::Pose2 WheelOdometry::Read(const geometry::Pose2& truth, Eigen::Matrix3d* covariance) {
  // The wheels measure the distance driven and the turn; the robot does not slip sideways, so
  // the translation is read along the direction it was driven.
  // Wheels that turn less than an encoder tick read nothing: standing still is exact.
  constexpr double kTick = 1e-9;  // m, or rad
  const Eigen::Vector2d t =
      truth.Translation().norm() < kTick ? Eigen::Vector2d::Zero() : truth.Translation();
  const double distance = t.norm();
  const Eigen::Vector2d along =
      distance > 0.0 ? Eigen::Vector2d(t / distance) : Eigen::Vector2d::UnitX();
  const double scale = options_.scale_error_percent / 100.0;
  const double turn_scale = options_.turn_scale_error_percent / 100.0;
  const double drift = options_.heading_drift_deg_per_m * kDegToRad;
  const double var_along = options_.noise_m_per_sqrt_m * options_.noise_m_per_sqrt_m * distance;
  const double heading_noise = options_.noise_deg_per_sqrt_m * kDegToRad;
  const double yaw = std::abs(truth.yaw) < kTick ? 0.0 : truth.yaw;
  const double turn_noise = options_.turn_noise_percent / 100.0 * std::abs(yaw);
  const double var_yaw = heading_noise * heading_noise * distance + turn_noise * turn_noise;

  const double read_distance = distance * (1.0 + scale) + std::sqrt(var_along) * unit_(rng_);
  const double read_yaw =
      yaw * (1.0 + turn_scale) + drift * distance + std::sqrt(var_yaw) * unit_(rng_);
  const Eigen::Vector2d read_t = read_distance * along;

  // The covariance a receiver should fuse with: the random part and the systematic errors'
  // size (a receiver does not know their sign).
  const double sd_along = std::sqrt(var_along + std::pow(scale * distance, 2));
  const double sd_yaw =
      std::sqrt(var_yaw + std::pow(turn_scale * yaw, 2) + std::pow(drift * distance, 2));
  covariance->setZero();
  covariance->topLeftCorner<2, 2>() = sd_along * sd_along * along * along.transpose();
  (*covariance)(2, 2) = sd_yaw * sd_yaw;
  return {read_t.x(), read_t.y(), read_yaw};
}

OdometryReading WheelOdometry::Step(const geometry::Pose2& true_pose) {
  OdometryReading out;
  out.seq = seq_++;
  if (out.seq > 0) {
    const geometry::Pose2 increment = Read(previous_true_.Inverse() * true_pose, &out.covariance);
    odometry_ = odometry_ * increment;
  }
  previous_true_ = true_pose;
  out.pose = odometry_;
  return out;
}

}  // namespace relplane::sim
