#pragma once
// Wheel odometry as the mapper takes it: the robot's motion between two plane sets, composed
// from the readings in between, with its covariance. The odometry frame drifts from the world,
// so only increments are used.

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <optional>

#include "relplane/common/geometry.hpp"

namespace relplane::mapper {

// One reading: the pose in the odometry frame and the covariance (x, y, yaw) of the increment
// since the previous reading, in the previous reading's robot frame.
struct OdometryReading {
  int64_t utime = 0;
  int64_t seq = 0;
  geometry::Pose2 pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// The motion from one plane set to the next as odometry read it: `motion` in the robot frame
// of the earlier reading, covariance of (x, y, yaw) in the same frame.
struct OdometryIncrement {
  geometry::Pose2 motion;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  int64_t from_utime = 0;  // the readings it spans
  int64_t to_utime = 0;
  bool readings_lost = false;  // a gap in seq: the covariance misses the lost readings' share
};

// Composes a then b (b in a's robot frame), propagating their independent covariances to
// first order: J_a Sa J_a^T + J_b Sb J_b^T.
void Compose(const geometry::Pose2& a, const Eigen::Matrix3d& cov_a, const geometry::Pose2& b,
             const Eigen::Matrix3d& cov_b, geometry::Pose2* out, Eigen::Matrix3d* cov_out);

// Collects readings as they arrive and hands out the increment up to each plane set's time.
class OdometryIntegrator {
 public:
  // Readings must come in increasing utime; an older or repeated one returns false and is
  // not used.
  bool Add(const OdometryReading& reading);
  // The motion from the last reading taken up to the previous call to the last reading at or
  // before `utime`; nothing when no reading came in between (or none before), or when the
  // readings' numbers overflow.
  std::optional<OdometryIncrement> TakeUntil(int64_t utime);

 private:
  std::deque<OdometryReading> pending_;
  std::optional<OdometryReading> last_taken_;  // the end of the previous increment
  int64_t last_utime_ = -1;
};

}  // namespace relplane::mapper
