#include "relplane/common/geometry.hpp"

#include <gtest/gtest.h>

#include <random>

namespace relplane::geometry {
namespace {

TEST(WrapAngle, StaysInHalfOpenInterval) {
  EXPECT_NEAR(WrapAngle(3 * M_PI), M_PI, 1e-12);
  EXPECT_NEAR(WrapAngle(-M_PI), M_PI, 1e-12);
  EXPECT_NEAR(WrapAngle(0.5 - 4 * M_PI), 0.5, 1e-12);
}

TEST(Pose2, ComposeWithInverseIsIdentity) {
  const Pose2 a{1.0, -2.0, 0.7};
  const Pose2 b{0.3, 0.4, -2.5};
  const Pose2 id = a * a.Inverse();
  EXPECT_NEAR(id.x, 0.0, 1e-12);
  EXPECT_NEAR(id.y, 0.0, 1e-12);
  EXPECT_NEAR(id.yaw, 0.0, 1e-12);
  // Composition agrees with the 3D isometry product, an independent computation.
  const Pose2 ab = a * b;
  const Eigen::Isometry3d iso = ToIsometry(a) * ToIsometry(b);
  const Pose2 back = ToPose2(iso);
  EXPECT_NEAR(ab.x, back.x, 1e-12);
  EXPECT_NEAR(ab.y, back.y, 1e-12);
  EXPECT_NEAR(ab.yaw, back.yaw, 1e-12);
}

TEST(Pose2, MapsPointsIntoParentFrame) {
  const Pose2 pose{1.0, 2.0, M_PI / 2};
  const Eigen::Vector2d p = pose * Eigen::Vector2d(1.0, 0.0);
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
}

TEST(Quaternion, WxyzRoundTripAndYaw) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitZ()));
  double wxyz[4];
  QuaternionToWxyz(q, wxyz);
  EXPECT_NEAR(wxyz[0], std::cos(0.45), 1e-12);
  EXPECT_NEAR(wxyz[3], std::sin(0.45), 1e-12);
  EXPECT_NEAR(YawOf(QuaternionFromWxyz(wxyz)), 0.9, 1e-12);
}

TEST(Plane, TransformKeepsPointsOnThePlane) {
  Plane plane{Eigen::Vector3d(1, 0, 0), -2.0};  // x = 2
  const Eigen::Isometry3d pose = ToIsometry(Pose2{0.5, -1.0, 0.3}, 1.0);
  const Plane world = plane.Transformed(pose);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(2, 5, -3)}) {
    EXPECT_NEAR(world.SignedDistance(pose * p), 0.0, 1e-12);
  }
}

TEST(Plane, FacingPointFlipsTowardsViewpoint) {
  const Plane plane{Eigen::Vector3d(1, 0, 0), -2.0};
  const Plane facing = plane.FacingPoint(Eigen::Vector3d::Zero());
  EXPECT_GT(facing.SignedDistance(Eigen::Vector3d::Zero()), 0.0);
  EXPECT_NEAR(facing.normal.x(), -1.0, 1e-12);
  EXPECT_NEAR(plane.AngleTo(facing, /*unsigned_normals=*/true), 0.0, 1e-9);
  EXPECT_NEAR(plane.AngleTo(facing), M_PI, 1e-9);
}

TEST(FitPlane, RecoversNoisyPlaneAndRms) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 0.5).normalized();
  const double d = -1.5;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 5000; ++i) {
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    p -= (n.dot(p) + d) * n;
    points.push_back(p + noise(rng) * n);
  }
  Plane plane;
  double rms = 0.0;
  ASSERT_TRUE(FitPlane(points, &plane, &rms));
  EXPECT_LT(plane.AngleTo(Plane{n, d}, true), 0.002);
  EXPECT_NEAR(std::abs(plane.d), std::abs(d), 0.002);
  EXPECT_NEAR(rms, 0.01, 0.001);
}

TEST(FitPlane, RejectsDegenerateInput) {
  Plane plane;
  EXPECT_FALSE(FitPlane({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX()}, &plane));
  EXPECT_FALSE(FitPlane({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                         Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(3, 0, 0)},
                        &plane));
}

TEST(Segment2, DistanceNormalAndAngle) {
  const Segment2 s{Eigen::Vector2d(0, 0), Eigen::Vector2d(4, 0)};
  EXPECT_NEAR(s.Length(), 4.0, 1e-12);
  EXPECT_NEAR(s.DistanceTo(Eigen::Vector2d(2, 3)), 3.0, 1e-12);
  EXPECT_NEAR(s.DistanceTo(Eigen::Vector2d(7, 4)), 5.0, 1e-12);
  EXPECT_NEAR(s.Normal().y(), 1.0, 1e-12);
  const Segment2 t{Eigen::Vector2d(0, 0), Eigen::Vector2d(-1, 1)};
  EXPECT_NEAR(LineAngle(s, t), M_PI / 4, 1e-12);
}

}  // namespace
}  // namespace relplane::geometry
