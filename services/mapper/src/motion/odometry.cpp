#include "relplane/mapper/odometry.hpp"

#include <cmath>

namespace relplane::mapper {

void Compose(const geometry::Pose2& a, const Eigen::Matrix3d& cov_a, const geometry::Pose2& b,
             const Eigen::Matrix3d& cov_b, geometry::Pose2* out, Eigen::Matrix3d* cov_out) {
  const double c = std::cos(a.yaw), s = std::sin(a.yaw);
  // d(a*b)/da: the translation of b turns with a's heading.
  Eigen::Matrix3d ja = Eigen::Matrix3d::Identity();
  ja(0, 2) = -s * b.x - c * b.y;
  ja(1, 2) = c * b.x - s * b.y;
  // d(a*b)/db: b's translation rotated into a's parent frame.
  Eigen::Matrix3d jb = Eigen::Matrix3d::Identity();
  jb.topLeftCorner<2, 2>() << c, -s, s, c;
  // Into temporaries first: out may be a, cov_out may be cov_a.
  const Eigen::Matrix3d cov = ja * cov_a * ja.transpose() + jb * cov_b * jb.transpose();
  const geometry::Pose2 pose = a * b;
  *cov_out = cov;
  *out = pose;
}

bool OdometryIntegrator::Add(const OdometryReading& reading) {
  if (reading.utime <= last_utime_) return false;
  last_utime_ = reading.utime;
  pending_.push_back(reading);
  return true;
}

std::optional<OdometryIncrement> OdometryIntegrator::TakeUntil(int64_t utime) {
  std::optional<OdometryIncrement> out;
  while (!pending_.empty() && pending_.front().utime <= utime) {
    const OdometryReading r = pending_.front();
    pending_.pop_front();
    if (!last_taken_) {  // the first reading only anchors the next increment
      last_taken_ = r;
      continue;
    }
    if (!out) {
      out = OdometryIncrement{};
      out->from_utime = last_taken_->utime;
    }
    // The poses give the increment exactly, lost readings or not; each reading's covariance is
    // that of its own step.
    const geometry::Pose2 step = last_taken_->pose.Inverse() * r.pose;
    Compose(out->motion, out->covariance, step, r.covariance, &out->motion, &out->covariance);
    out->readings_lost = out->readings_lost || r.seq != last_taken_->seq + 1;
    out->to_utime = r.utime;
    last_taken_ = r;
  }
  // Readings far beyond any room (hostile or broken) overflow: no increment rather than a
  // non-finite one.
  if (out && !(std::isfinite(out->motion.x) && std::isfinite(out->motion.y) &&
               std::isfinite(out->motion.yaw) && out->covariance.allFinite())) {
    return std::nullopt;
  }
  return out;
}

}  // namespace relplane::mapper
