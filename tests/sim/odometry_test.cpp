// The wheel odometry error model: its systematic errors, its noise's statistics against the
// covariance it claims, and its determinism.
#include "relplane/sim/odometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "angles.hpp"

namespace relplane::sim {
namespace {

using testing::kDeg;

OdometryOptions Quiet() {
  OdometryOptions o;
  o.enabled = true;
  o.scale_error_percent = 0.0;
  o.turn_scale_error_percent = 0.0;
  o.heading_drift_deg_per_m = 0.0;
  o.noise_m_per_sqrt_m = 0.0;
  o.noise_deg_per_sqrt_m = 0.0;
  o.turn_noise_percent = 0.0;
  return o;
}

// Drives `n` steps of `step` (in the robot frame) and returns the last reading.
OdometryReading Drive(const OdometryOptions& o, const geometry::Pose2& step, int n) {
  WheelOdometry odometry(o, {});
  geometry::Pose2 truth;
  OdometryReading last = odometry.Step(truth);
  for (int i = 0; i < n; ++i) {
    truth = truth * step;
    last = odometry.Step(truth);
  }
  return last;
}

TEST(WheelOdometry, WithoutErrorsItReadsTheTruth) {
  const OdometryReading r = Drive(Quiet(), {0.03, 0.0, 0.01}, 300);
  geometry::Pose2 truth;
  for (int i = 0; i < 300; ++i) truth = truth * geometry::Pose2{0.03, 0.0, 0.01};
  EXPECT_NEAR(r.pose.x, truth.x, 1e-9);
  EXPECT_NEAR(r.pose.y, truth.y, 1e-9);
  EXPECT_NEAR(r.pose.yaw, truth.yaw, 1e-9);
  EXPECT_EQ(r.seq, 300);
}

TEST(WheelOdometry, ScaleErrorAndHeadingDriftAreInTheirNamedUnits) {
  OdometryOptions o = Quiet();
  o.scale_error_percent = 2.0;
  const OdometryReading straight = Drive(o, {0.01, 0.0, 0.0}, 1000);  // 10 m
  EXPECT_NEAR(straight.pose.x, 10.2, 1e-9);
  o = Quiet();
  o.heading_drift_deg_per_m = 0.5;
  const OdometryReading drifted = Drive(o, {0.01, 0.0, 0.0}, 1000);
  EXPECT_NEAR(drifted.pose.yaw, 5.0 * kDeg, 1e-9);
  o = Quiet();
  o.turn_scale_error_percent = 10.0;
  const OdometryReading turned = Drive(o, {0.0, 0.0, M_PI / 200}, 100);  // a quarter turn...
  EXPECT_NEAR(turned.pose.yaw, 0.55 * M_PI, 1e-9);                       // read 10 % large
  EXPECT_NEAR(turned.pose.x, 0.0, 1e-12);                                // on the spot
}

TEST(WheelOdometry, NoiseMatchesTheCovarianceItClaims) {
  // Many independent increments: the errors' spread equals the claimed sigma, along the
  // motion and in heading, and their mean is zero.
  OdometryOptions o = Quiet();
  o.noise_m_per_sqrt_m = 0.01;
  o.noise_deg_per_sqrt_m = 0.5;
  o.turn_noise_percent = 2.0;
  WheelOdometry odometry(o, {});
  const geometry::Pose2 step{0.05, 0.0, 0.02};
  const int n = 20000;
  double sum_d = 0, sum_dd = 0, sum_y = 0, sum_yy = 0, claimed_d = 0, claimed_y = 0;
  for (int i = 0; i < n; ++i) {
    Eigen::Matrix3d c;
    const geometry::Pose2 read = odometry.Read(step, &c);
    const double ed = read.x - step.x, ey = read.yaw - step.yaw;
    sum_d += ed, sum_dd += ed * ed, sum_y += ey, sum_yy += ey * ey;
    claimed_d = c(0, 0), claimed_y = c(2, 2);
    EXPECT_NEAR(read.y, 0.0, 1e-15);  // no sideways slip
  }
  const double expected_d = 0.01 * 0.01 * 0.05;
  const double expected_y = std::pow(0.5 * kDeg, 2) * 0.05 + std::pow(0.02 * 0.02, 2);
  EXPECT_NEAR(claimed_d, expected_d, 1e-15);
  EXPECT_NEAR(claimed_y, expected_y, 1e-15);
  EXPECT_NEAR(sum_d / n, 0.0, 4.0 * std::sqrt(expected_d / n));
  EXPECT_NEAR(sum_y / n, 0.0, 4.0 * std::sqrt(expected_y / n));
  EXPECT_NEAR(sum_dd / n / expected_d, 1.0, 0.04);
  EXPECT_NEAR(sum_yy / n / expected_y, 1.0, 0.04);
}

TEST(WheelOdometry, SystematicErrorsAreCoveredByTheCovariance) {
  // Defaults: the claimed sigma includes the systematic errors' size, so the error of a 1 m
  // straight stays within 3 sigma.
  OdometryOptions o;
  o.enabled = true;
  WheelOdometry odometry(o, {});
  Eigen::Matrix3d c;
  const geometry::Pose2 read = odometry.Read({1.0, 0.0, 0.0}, &c);
  EXPECT_LE(std::abs(read.x - 1.0), 3.0 * std::sqrt(c(0, 0)));
  EXPECT_LE(std::abs(read.yaw), 3.0 * std::sqrt(c(2, 2)));
  EXPECT_GT(std::sqrt(c(0, 0)), 0.01 - 1e-12);  // at least the 1 % scale error
}

TEST(WheelOdometry, StandingStillReadsNothing) {
  OdometryOptions o;  // defaults, noise on
  WheelOdometry odometry(o, {1.0, 2.0, 0.3});
  odometry.Step({1.0, 2.0, 0.3});
  const OdometryReading r = odometry.Step({1.0, 2.0, 0.3});
  EXPECT_NEAR(r.pose.x, 1.0, 1e-12);
  EXPECT_NEAR(r.pose.y, 2.0, 1e-12);
  EXPECT_NEAR(r.pose.yaw, 0.3, 1e-12);
  EXPECT_TRUE(r.covariance.isZero());
}

TEST(WheelOdometry, TheSeedDecidesTheDraws) {
  OdometryOptions a;
  a.enabled = true;
  const OdometryReading first = Drive(a, {0.03, 0.0, 0.01}, 100);
  const OdometryReading again = Drive(a, {0.03, 0.0, 0.01}, 100);
  EXPECT_EQ(first.pose.x, again.pose.x);
  EXPECT_EQ(first.pose.yaw, again.pose.yaw);
  a.seed = 2;
  const OdometryReading other = Drive(a, {0.03, 0.0, 0.01}, 100);
  EXPECT_NE(first.pose.x, other.pose.x);
}

}  // namespace
}  // namespace relplane::sim
