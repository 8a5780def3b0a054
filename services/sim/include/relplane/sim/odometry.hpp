#pragma once
// Simulated wheel odometry of a differential-drive robot (ODOMETRY, when a scenario asks for
// it): the true motion between two readings, read with a systematic scale error, a heading
// drift per metre driven and random noise that grows with the distance and the turn. The robot
// frame is the sensor's floor-plan pose. Deterministic: the draws depend on the seed only.

#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "relplane/common/geometry.hpp"

namespace relplane::sim {

// Defaults of the order of a calibrated indoor differential-drive robot (wheel radii and
// track width known to about 1 %).
struct OdometryOptions {
  bool enabled = false;
  double rate_hz = 0.0;  // readings per simulated second; 0: one per iteration (sim.rate_hz)
  // Systematic: every distance reads this much long (negative: short), and every turn this
  // much too large (a track width off by that much).
  double scale_error_percent = 1.0;
  double turn_scale_error_percent = 1.0;
  // Systematic: the heading turns this much per metre driven (unequal wheel radii).
  double heading_drift_deg_per_m = 0.5;
  // Random walk: one sigma after 1 m of straight driving.
  double noise_m_per_sqrt_m = 0.005;  // along the motion
  double noise_deg_per_sqrt_m = 0.2;  // of the heading
  double turn_noise_percent = 1.0;    // of the heading, one sigma, of each turn increment
  uint64_t seed = 1;
};

// One reading: the pose in the odometry frame (which starts at the robot's true start pose
// and drifts from it) and the covariance of the increment since the previous reading, in
// (x, y, yaw) of the previous reading's robot frame.
struct OdometryReading {
  int64_t seq = 0;
  geometry::Pose2 pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

class WheelOdometry {
 public:
  WheelOdometry(const OdometryOptions& options, const geometry::Pose2& start);

  // The reading after the robot moved from the previous true pose to `true_pose`. The first
  // call (seq 0) reads the start with a zero covariance.
  OdometryReading Step(const geometry::Pose2& true_pose);

  // The increment as read from a true increment (previous robot frame), with its covariance.
  // Draws from the generator; public for the error model's tests.
  geometry::Pose2 Read(const geometry::Pose2& truth, Eigen::Matrix3d* covariance);

 private:
  OdometryOptions options_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_{0.0, 1.0};
  geometry::Pose2 previous_true_;
  geometry::Pose2 odometry_;
  int64_t seq_ = 0;
};

}  // namespace relplane::sim
