// Simulator types -> messages.

#include "convert.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace relplane::sim {
namespace {

TEST(Convert, PointCloudKeepsEveryPointInOrder) {
  Scan scan;
  scan.points = {{1, 2, 3}, {4, 5, 6}};
  scan.rects = {0, 1};
  const point_cloud_t msg = ToPointCloud(scan, 7, 233333);
  EXPECT_EQ(msg.seq, 7);
  EXPECT_EQ(msg.utime, 233333);
  ASSERT_EQ(msg.num_points, 2);
  EXPECT_EQ(msg.x[1], 4.0f);
  EXPECT_EQ(msg.y[1], 5.0f);
  EXPECT_EQ(msg.z[0], 3.0f);
}

TEST(Convert, TruthPoseIsWorldFromSensor) {
  const Eigen::Isometry3d pose = geometry::ToIsometry(geometry::Pose2{1, 2, 0.5}, 1.0);
  const pose_t msg = ToTruthPose(pose, 3, 100000);
  EXPECT_EQ(+msg.status, +pose_t::STATUS_TRUTH);  // + avoids odr-using the constant
  EXPECT_EQ(msg.seq, 3);
  EXPECT_DOUBLE_EQ(msg.position[0], 1.0);
  EXPECT_DOUBLE_EQ(msg.position[2], 1.0);
  EXPECT_NEAR(msg.orientation[0], std::cos(0.25), 1e-12);  // w
  EXPECT_NEAR(msg.orientation[3], std::sin(0.25), 1e-12);  // z
}

TEST(Convert, TruthCovarianceIsZero) {
  pose_t msg = ToTruthPose(Eigen::Isometry3d::Identity(), 0, 0);
  for (double v : msg.covariance) EXPECT_EQ(v, 0.0);
}

TEST(Convert, OdometryCarriesPoseAndIncrementCovariance) {
  OdometryReading r;
  r.seq = 4;
  r.pose = {1.0, -2.0, 0.5};
  r.covariance << 1e-4, 0, 0, 0, 2e-4, 0, 0, 0, 3e-6;
  r.covariance(0, 1) = r.covariance(1, 0) = 5e-5;
  const odometry_t msg = ToOdometry(r, 133333);
  EXPECT_EQ(msg.seq, 4);
  EXPECT_EQ(msg.utime, 133333);
  EXPECT_EQ(msg.position[0], 1.0);
  EXPECT_EQ(msg.position[1], -2.0);
  EXPECT_EQ(msg.position[2], 0.0);
  EXPECT_NEAR(msg.orientation[0], std::cos(0.25), 1e-12);
  EXPECT_NEAR(msg.orientation[3], std::sin(0.25), 1e-12);
  EXPECT_EQ(msg.covariance[1], 5e-5);  // row-major
  EXPECT_EQ(msg.covariance[4], 2e-4);
  EXPECT_EQ(msg.covariance[8], 3e-6);
}

TEST(Convert, WorldMapHasOnePlanePerRectangle) {
  WorldOptions options;
  options.generators = {HallwayLoopParams{}};
  const World world = BuildWorld(options);
  const map_t msg = ToWorldMap(TruePlanes(world), 0, 0);
  ASSERT_EQ(msg.num_planes, 10);
  EXPECT_EQ(msg.num_groups, 0);
  int walls = 0;
  for (int i = 0; i < msg.num_planes; ++i) {
    const plane_t& p = msg.planes[i];
    EXPECT_EQ(p.id, i);
    ASSERT_EQ(p.num_vertices, 4);
    EXPECT_EQ(p.num_points, 0);
    for (const auto& v : p.vertices) {
      EXPECT_NEAR(p.normal[0] * v[0] + p.normal[1] * v[1] + p.normal[2] * v[2] + p.d, 0, 1e-5);
    }
    walls += std::abs(p.normal[2]) < 0.1 ? 1 : 0;
  }
  EXPECT_EQ(walls, 8);
}

}  // namespace
}  // namespace relplane::sim
