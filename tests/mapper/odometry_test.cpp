// Odometry increments between plane sets: composition, covariance propagation, timing.
#include "relplane/mapper/odometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace relplane::mapper {
namespace {

OdometryReading Reading(int64_t seq, geometry::Pose2 pose, double var = 1e-4) {
  OdometryReading r;
  r.utime = 1000 * seq;
  r.seq = seq;
  r.pose = pose;
  r.covariance = Eigen::Vector3d(var, var, var).asDiagonal();
  return r;
}

TEST(Odometry, IncrementIsTheMotionBetweenPlaneSetsInTheEarlierRobotFrame) {
  OdometryIntegrator odometry;
  // The odometry frame is anywhere: in it the robot moves 1 m along x while turning.
  const geometry::Pose2 frame{5.0, -3.0, 1.0};
  for (int k = 0; k <= 10; ++k) {
    ASSERT_TRUE(odometry.Add(Reading(k, frame * geometry::Pose2{0.1 * k, 0.0, 0.02 * k})));
  }
  EXPECT_FALSE(odometry.TakeUntil(0).has_value());  // the first reading only anchors
  const auto inc = odometry.TakeUntil(5000);
  ASSERT_TRUE(inc.has_value());
  EXPECT_NEAR(inc->motion.x, 0.5, 1e-12);
  EXPECT_NEAR(inc->motion.y, 0.0, 1e-12);
  EXPECT_NEAR(inc->motion.yaw, 0.1, 1e-12);
  EXPECT_EQ(inc->from_utime, 0);
  EXPECT_EQ(inc->to_utime, 5000);
  EXPECT_FALSE(inc->readings_lost);
  // From the reading at 5000, heading 0.1 rad off the frame's x along which the robot moves.
  const auto next = odometry.TakeUntil(10000);
  ASSERT_TRUE(next.has_value());
  EXPECT_NEAR(next->motion.x, 0.5 * std::cos(0.1), 1e-12);
  EXPECT_NEAR(next->motion.y, -0.5 * std::sin(0.1), 1e-12);
  EXPECT_FALSE(odometry.TakeUntil(20000).has_value());  // nothing new
}

TEST(Odometry, ReadingsAfterThePlaneSetWaitForTheNext) {
  OdometryIntegrator odometry;
  odometry.Add(Reading(0, {}));
  odometry.Add(Reading(1, {0.1, 0, 0}));
  odometry.Add(Reading(2, {0.2, 0, 0}));
  const auto inc = odometry.TakeUntil(1500);
  ASSERT_TRUE(inc.has_value());
  EXPECT_NEAR(inc->motion.x, 0.1, 1e-12);
  EXPECT_FALSE(odometry.Add(Reading(2, {0.3, 0, 0})));  // repeated time: refused
}

TEST(Odometry, ALostReadingIsFlaggedAndTheMotionStillExact) {
  OdometryIntegrator odometry;
  odometry.Add(Reading(0, {}));
  odometry.Add(Reading(3, {0.3, 0.1, 0.05}));
  const auto inc = odometry.TakeUntil(3000);
  ASSERT_TRUE(inc.has_value());
  EXPECT_TRUE(inc->readings_lost);
  EXPECT_NEAR(inc->motion.x, 0.3, 1e-12);
  EXPECT_NEAR(inc->motion.y, 0.1, 1e-12);
}

TEST(Odometry, ComposedCovarianceMatchesSampledMotion) {
  // Against an independent computation: sample noisy steps, compose them exactly, and compare
  // the spread with the first-order propagation.
  const geometry::Pose2 step{0.2, 0.0, 0.15};
  Eigen::Matrix3d step_cov = Eigen::Vector3d(1e-5, 4e-6, 2e-6).asDiagonal();
  step_cov(0, 2) = step_cov(2, 0) = 1e-6;
  geometry::Pose2 mean;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 10; ++i) Compose(mean, cov, step, step_cov, &mean, &cov);

  std::mt19937_64 rng(3);
  std::normal_distribution<double> unit(0.0, 1.0);
  const Eigen::Matrix3d l = step_cov.llt().matrixL();
  Eigen::Matrix3d sampled = Eigen::Matrix3d::Zero();
  const int n = 20000;
  for (int s = 0; s < n; ++s) {
    geometry::Pose2 p;
    for (int i = 0; i < 10; ++i) {
      const Eigen::Vector3d e = l * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      p = p * geometry::Pose2{step.x + e.x(), step.y + e.y(), step.yaw + e.z()};
    }
    const Eigen::Vector3d d(p.x - mean.x, p.y - mean.y, geometry::WrapAngle(p.yaw - mean.yaw));
    sampled += d * d.transpose() / n;
  }
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(sampled(r, r) / cov(r, r), 1.0, 0.05) << r;
  }
  EXPECT_NEAR(sampled(0, 1), cov(0, 1), 0.05 * std::sqrt(cov(0, 0) * cov(1, 1)));
}

}  // namespace
}  // namespace relplane::mapper
