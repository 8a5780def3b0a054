// Observability (Zhang, Kaess, Singh, ICRA 2016) on hand-built constraint sets: which of
// (x, y, yaw) walls in view fix, which they leave open, and the covariance that says so.
#include "relplane/mapper/observability.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace relplane::mapper {
namespace {

constexpr double kSigma = 0.01;          // m, a wall's line
constexpr double kHeadingSigma = 0.002;  // rad

// A wall's line seen at `point` (world frame, relative to the sensor) with unit normal at
// angle `alpha`: the residual n . (c + R m) - n . P changes by n along (x, y) and by n . (R' m)
// with the heading, R' m = point rotated by +90 degrees.
PoseConstraint Wall(double alpha, const Eigen::Vector2d& point, double sigma = kSigma) {
  const Eigen::Vector2d n(std::cos(alpha), std::sin(alpha));
  const Eigen::Vector2d lever(-point.y(), point.x());
  return {Eigen::Vector3d(n.x(), n.y(), n.dot(lever)), sigma};
}

// A wall end seen at `point`: fixes the position along the wall's direction `t`.
PoseConstraint End(double along_angle, const Eigen::Vector2d& point, double sigma = kSigma) {
  return Wall(along_angle, point, sigma);
}

PoseConstraint Heading(double sigma = kHeadingSigma) { return {Eigen::Vector3d::UnitZ(), sigma}; }

// |cosine| between a direction and an axis.
double Alignment(const Eigen::Vector3d& v, const Eigen::Vector3d& axis) {
  return std::abs(v.normalized().dot(axis.normalized()));
}

TEST(Observability, TwoPerpendicularWallsWithHeadingFixEverything) {
  const Observability o =
      AnalyseObservability({Wall(0.0, {2.0, 0.5}), Wall(M_PI / 2, {0.5, 3.0}), Heading()});
  EXPECT_TRUE(o.FullyConstrained());
  EXPECT_NEAR(std::sqrt(o.covariance(0, 0)), kSigma, 0.2 * kSigma);
  EXPECT_NEAR(std::sqrt(o.covariance(1, 1)), kSigma, 0.2 * kSigma);
  EXPECT_NEAR(std::sqrt(o.covariance(2, 2)), kHeadingSigma, 0.2 * kHeadingSigma);
}

TEST(Observability, TwoPerpendicularLinesAloneLeaveTheHeadingOpen) {
  // Two lines fix a point for each heading, not the heading: one direction is open, and it is
  // mostly yaw (x and y follow it through the lever arms).
  const Observability o = AnalyseObservability({Wall(0.0, {2.0, 0.5}), Wall(M_PI / 2, {0.5, 3.0})});
  ASSERT_EQ(o.unconstrained.size(), 1u);
  const Eigen::Vector3d v = o.unconstrained[0];
  // Along v the lines do not change: J v = 0 for both.
  EXPECT_NEAR(Wall(0.0, {2.0, 0.5}).jacobian.dot(v), 0.0, 1e-9);
  EXPECT_NEAR(Wall(M_PI / 2, {0.5, 3.0}).jacobian.dot(v), 0.0, 1e-9);
  EXPECT_GT(std::sqrt(o.covariance(2, 2)), 0.3);  // near the 0.5 rad prior
}

TEST(Observability, OneWallLeavesTheDirectionAlongItOpen) {
  const Observability o = AnalyseObservability({Wall(0.0, {2.0, 0.0}), Heading()});
  ASSERT_EQ(o.unconstrained.size(), 1u);
  EXPECT_GT(Alignment(o.unconstrained[0], Eigen::Vector3d::UnitY()), 0.999);
  EXPECT_NEAR(std::sqrt(o.covariance(1, 1)), ObservabilityOptions{}.prior_sigma_position, 1e-3);
  EXPECT_NEAR(std::sqrt(o.covariance(0, 0)), kSigma, 0.1 * kSigma);
}

TEST(Observability, CorridorOfParallelWallsLeavesItsAxisOpen) {
  // A corridor along y: walls at x = -1 and x = +1, normals +-x, seen 2 m ahead.
  const Observability o =
      AnalyseObservability({Wall(0.0, {1.0, 2.0}), Wall(M_PI, {-1.0, 2.0}), Heading()});
  ASSERT_EQ(o.unconstrained.size(), 1u);
  EXPECT_GT(Alignment(o.unconstrained[0], Eigen::Vector3d::UnitY()), 0.999);
  EXPECT_GT(o.covariance(1, 1), 100.0 * o.covariance(0, 0));
}

TEST(Observability, ADoorEdgeClosesTheCorridor) {
  // The static edge of a door opening fixes the position along the corridor.
  const Observability o = AnalyseObservability(
      {Wall(0.0, {1.0, 2.0}), Wall(M_PI, {-1.0, 2.0}), End(M_PI / 2, {1.0, 1.5}), Heading()});
  EXPECT_TRUE(o.FullyConstrained());
  EXPECT_LT(std::sqrt(o.covariance(1, 1)), 2.0 * kSigma);
}

TEST(Observability, WallsNearlyParallelAreStillWeakAlongTheirBisector) {
  // Two walls 2 degrees apart, each good to 1 cm, fix the position along their common
  // direction only to about 1 cm / sin(1 degree) ~ 0.4 m: open.
  const double a = 2.0 * M_PI / 180.0;
  const Observability weak =
      AnalyseObservability({Wall(0.0, {2.0, 0.0}), Wall(a, {2.0, 1.0}), Heading()});
  EXPECT_EQ(weak.unconstrained.size(), 1u);
  // 30 degrees apart: fixed.
  const double b = 30.0 * M_PI / 180.0;
  const Observability fixed =
      AnalyseObservability({Wall(0.0, {2.0, 0.0}), Wall(b, {2.0, 1.0}), Heading()});
  EXPECT_TRUE(fixed.FullyConstrained());
}

TEST(Observability, CovarianceIsTheInverseWhereTheConstraintsDominate) {
  // Against an independent computation: with strong constraints the prior barely counts, so the
  // covariance is the inverse of the information to within the prior's share.
  const std::vector<PoseConstraint> c = {Wall(0.0, {2.0, 0.5}), Wall(M_PI / 2, {0.5, 3.0}),
                                         Wall(M_PI / 4, {1.0, 1.0}), Heading()};
  const Observability o = AnalyseObservability(c);
  const Eigen::Matrix3d expected = InformationOf(c).inverse();
  EXPECT_TRUE(o.covariance.isApprox(expected, 1e-3)) << o.covariance << "\n" << expected;
  EXPECT_TRUE(o.covariance.isApprox(o.covariance.transpose(), 1e-12));
}

TEST(Observability, NothingInViewGivesThePrior) {
  const ObservabilityOptions options;
  const Observability o = AnalyseObservability(std::vector<PoseConstraint>{}, options);
  EXPECT_EQ(o.unconstrained.size(), 3u);
  EXPECT_NEAR(o.covariance(0, 0), std::pow(options.prior_sigma_position, 2), 1e-12);
  EXPECT_NEAR(o.covariance(2, 2), std::pow(options.prior_sigma_yaw, 2), 1e-12);
}

TEST(Observability, BadConstraintsAndMatricesAddNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<PoseConstraint> bad = {{Eigen::Vector3d(nan, 0, 0), 0.01},
                                           {Eigen::Vector3d::UnitX(), 0.0},
                                           {Eigen::Vector3d::UnitX(), nan}};
  EXPECT_TRUE(InformationOf(bad).isZero());
  Eigen::Matrix3d asymmetric = Eigen::Matrix3d::Identity();
  asymmetric(0, 1) = 5.0;
  EXPECT_EQ(AnalyseInformation(asymmetric).unconstrained.size(), 3u);
  Eigen::Matrix3d with_nan = Eigen::Matrix3d::Identity() * 1e6;
  with_nan(2, 2) = nan;
  const Observability o = AnalyseInformation(with_nan);
  EXPECT_TRUE(o.covariance.allFinite());
  EXPECT_EQ(o.unconstrained.size(), 3u);
}

}  // namespace
}  // namespace relplane::mapper
