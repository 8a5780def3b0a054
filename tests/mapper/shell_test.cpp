// The service shell: PLANES -> mapper input (bad input refused with a reason), mapper output
// -> POSE/MAP, and the `mapper` options section.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "convert.hpp"
#include "options_yaml.hpp"

namespace relplane::mapper {
namespace {

plane_t Plane(float x) {
  plane_t p{};
  p.id = 0;
  p.normal[0] = -1, p.normal[1] = 0, p.normal[2] = 0;
  p.d = x;
  p.centroid[0] = x, p.centroid[1] = 0, p.centroid[2] = 0;
  p.vertices = {{x, -1, -1}, {x, 1, -1}, {x, 1, 1}, {x, -1, 1}};
  p.num_vertices = 4;
  return p;
}

TEST(Convert, PlaneSetRoundTripAndBadInput) {
  plane_set_t set{};
  set.seq = 3;
  set.planes = {Plane(3.0f)};
  set.num_planes = 1;
  std::vector<PlaneInput> planes;
  std::string reason;
  ASSERT_TRUE(FromPlaneSet(set, &planes, &reason));
  ASSERT_EQ(planes.size(), 1u);
  EXPECT_EQ(planes[0].vertices.size(), 4u);
  set.planes[0].d = std::nanf("");
  EXPECT_FALSE(FromPlaneSet(set, &planes, &reason));
  EXPECT_NE(reason.find("non-finite"), std::string::npos);
  set.planes[0] = Plane(3.0f);
  set.planes[0].normal[0] = 0;
  EXPECT_FALSE(FromPlaneSet(set, &planes, &reason));
  EXPECT_NE(reason.find("zero normal"), std::string::npos);
  set.num_planes = 2;
  EXPECT_FALSE(FromPlaneSet(set, &planes, &reason));
}

TEST(Convert, PoseAndMapMessages) {
  PoseEstimate est;
  est.pose = {1.0, 2.0, M_PI / 2};
  est.status = PoseStatus::kMotionModel;
  Eigen::Matrix3d covariance;
  covariance << 1e-4, 2e-5, 0, 2e-5, 1.0, 3e-6, 0, 3e-6, 1e-6;
  const pose_t pose = ToPoseMessage(est, covariance, 1.0, 100, 3);
  // Row-major (x, y, yaw) as pose_t.lcm documents it.
  EXPECT_EQ(pose.covariance[1], 2e-5);
  EXPECT_EQ(pose.covariance[4], 1.0);
  EXPECT_EQ(pose.covariance[5], 3e-6);
  EXPECT_EQ(pose.covariance[8], 1e-6);
  EXPECT_EQ(pose.seq, 3);
  EXPECT_EQ(pose.utime, 100);
  EXPECT_EQ(pose.status, static_cast<int8_t>(pose_t::STATUS_MOTION_MODEL));
  EXPECT_DOUBLE_EQ(pose.position[2], 1.0);
  EXPECT_NEAR(pose.orientation[0], std::cos(M_PI / 4), 1e-12);
  MapSnapshot map;
  map.planes.push_back(
      {7, {0, 1, 0}, -1, {0, 1, 1}, {{0, 1, 0}, {1, 1, 0}, {1, 1, 2}, {0, 1, 2}}, 12});
  map.groups.push_back({0, 7, {7}});
  const map_t msg = ToMapMessage(map, 100, 3);
  ASSERT_EQ(msg.num_planes, 1);
  EXPECT_EQ(msg.planes[0].id, 7);
  EXPECT_EQ(msg.planes[0].num_vertices, 4);
  EXPECT_EQ(msg.planes[0].num_points, 12);
  ASSERT_EQ(msg.num_groups, 1);
  EXPECT_EQ(msg.groups[0].basis_id, 7);
}

TEST(Options, ReadsTheSectionAndRefusesUnknownKeys) {
  const std::string file = ::testing::TempDir() + "mapper_options.yaml";
  std::ofstream(file)
      << "name: x\nmapper:\n  start_pose: {x: 1, y: 2, z: 1.0, yaw: 0.5}\n"
         "  grouping: {min_observations: 5}\n  published_map: {corner_radius: 0.05}\n"
         "  graph: {angle_sigma: 0.004, max_pose_ties: 20}\n"
         "  motion: {turn_rate: 0.02}\n";
  const MapperOptions o = LoadMapperOptions(file);
  EXPECT_DOUBLE_EQ(o.published_map.corner_radius, 0.05);
  // mapper.graph.* is settable (it was rejected as an unknown key once).
  EXPECT_DOUBLE_EQ(o.graph.angle_sigma, 0.004);
  EXPECT_EQ(o.graph.max_pose_ties, 20);
  EXPECT_DOUBLE_EQ(o.graph.position_sigma, PoseGraphOptions{}.position_sigma);
  EXPECT_DOUBLE_EQ(o.motion.turn_rate, 0.02);
  EXPECT_DOUBLE_EQ(o.start_pose.z, 1.0);
  EXPECT_DOUBLE_EQ(o.start_pose.yaw, 0.5);
  EXPECT_EQ(o.grouping.min_observations, 5);
  std::ofstream(file) << "mapper:\n  grouping: {min_observatons: 5}\n";
  EXPECT_THROW(LoadMapperOptions(file), config::ConfigError);
  std::ofstream(file) << "mapper:\n  comparison: {static_std: -1}\n";
  EXPECT_THROW(LoadMapperOptions(file), config::ConfigError);
  std::ofstream(file) << "mapper:\n  published_map: {corner_radius: -0.1}\n";
  EXPECT_THROW(LoadMapperOptions(file), config::ConfigError);
  std::ofstream(file) << "mapper:\n  graph: {angle_sigma: 0}\n";
  EXPECT_THROW(LoadMapperOptions(file), config::ConfigError);
  std::ofstream(file) << "mapper:\n  graph: {angel_sigma: 0.1}\n";
  EXPECT_THROW(LoadMapperOptions(file), config::ConfigError);
  std::remove(file.c_str());
}

TEST(Options, TheGlobalMapsAndRelativeMapsWeighingIsSettable) {
  const std::string file = ::testing::TempDir() + "mapper_weighing.yaml";
  std::ofstream(file) << "mapper:\n  global_map: {edge_gate: 0.3, pose_noise: 0.02}\n"
                         "  comparison: {spread_scale: 0.01, parallel_sin: 0.1}\n"
                         "  localisation: {open_information: 0.05}\n";
  const MapperOptions o = LoadMapperOptions(file);
  EXPECT_DOUBLE_EQ(o.global_map.edge_gate, 0.3);
  EXPECT_DOUBLE_EQ(o.global_map.pose_noise, 0.02);
  EXPECT_DOUBLE_EQ(o.global_map.line_noise, GlobalMapOptions{}.line_noise);
  EXPECT_DOUBLE_EQ(o.comparison.spread_scale, 0.01);
  EXPECT_DOUBLE_EQ(o.comparison.parallel_sin, 0.1);
  EXPECT_DOUBLE_EQ(o.localisation.open_information, 0.05);
  for (const char* bad : {"global_map: {edge_gate: 0}", "global_map: {spans_open: 1.5}",
                          "global_map: {edge_gates: 0.5}", "comparison: {parallel_sin: 1}",
                          "localisation: {open_information: -0.02}"}) {
    std::ofstream(file) << "mapper:\n  " << bad << "\n";
    EXPECT_THROW(LoadMapperOptions(file), config::ConfigError) << bad;
  }
  std::remove(file.c_str());
}

TEST(Options, TheFitViewAndLengthModelsAreSettable) {
  const std::string file = ::testing::TempDir() + "mapper_models.yaml";
  std::ofstream(file) << "mapper:\n  fit: {orientation_floor: 0.002, piece_blur: 0.05}\n"
                         "  rltplane: {noise_hysteresis: 2.5, smoothing: 7}\n"
                         "  view: {bearing_margin: 0.05, min_pile: 30}\n"
                         "  comparison: {pooled_std: 0.02}\n";
  const MapperOptions o = LoadMapperOptions(file);
  EXPECT_DOUBLE_EQ(o.fit.orientation_floor, 0.002);
  EXPECT_DOUBLE_EQ(o.fit.piece_blur, 0.05);
  EXPECT_DOUBLE_EQ(o.rltplane.noise_hysteresis, 2.5);
  EXPECT_EQ(o.rltplane.smoothing, 7);
  EXPECT_EQ(o.rltplane.full_length_sightings, RltPlaneOptions{}.full_length_sightings);
  EXPECT_DOUBLE_EQ(o.view.bearing_margin, 0.05);
  EXPECT_EQ(o.view.min_pile, 30);
  EXPECT_DOUBLE_EQ(o.comparison.pooled_std, 0.02);
  for (const char* bad :
       {"fit: {piece_blur: 0}", "fit: {orientation_flor: 0.001}", "rltplane: {smoothing: 2}",
        "rltplane: {retired_lengths: 1}", "view: {min_pile: 0}", "view: {pile_contrast: -1}",
        "comparison: {pooled_std: 0}"}) {
    std::ofstream(file) << "mapper:\n  " << bad << "\n";
    EXPECT_THROW(LoadMapperOptions(file), config::ConfigError) << bad;
  }
  std::remove(file.c_str());
}

}  // namespace
}  // namespace relplane::mapper

namespace relplane::mapper {
namespace {

odometry_t OdometryMessage() {
  odometry_t msg{};
  msg.utime = 33333;
  msg.seq = 1;
  msg.position[0] = 1.0;
  msg.position[1] = 2.0;
  msg.orientation[0] = std::cos(0.2);
  msg.orientation[3] = std::sin(0.2);
  msg.covariance[0] = msg.covariance[4] = 1e-4;
  msg.covariance[8] = 1e-6;
  return msg;
}

TEST(Convert, OdometryReadingsAreCheckedLikeAnyInput) {
  OdometryReading r;
  std::string reason;
  ASSERT_TRUE(FromOdometry(OdometryMessage(), &r, &reason)) << reason;
  EXPECT_EQ(r.utime, 33333);
  EXPECT_EQ(r.seq, 1);
  EXPECT_NEAR(r.pose.yaw, 0.4, 1e-12);
  EXPECT_EQ(r.covariance(1, 1), 1e-4);
  odometry_t bad = OdometryMessage();
  bad.position[1] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(FromOdometry(bad, &r, &reason));
  EXPECT_NE(reason.find("non-finite"), std::string::npos);
  bad = OdometryMessage();
  for (double& v : bad.orientation) v = 0.0;
  EXPECT_FALSE(FromOdometry(bad, &r, &reason));
  EXPECT_NE(reason.find("quaternion"), std::string::npos);
  bad = OdometryMessage();
  bad.covariance[0] = -1.0;
  EXPECT_FALSE(FromOdometry(bad, &r, &reason));
  EXPECT_NE(reason.find("covariance"), std::string::npos);
}

}  // namespace
}  // namespace relplane::mapper
