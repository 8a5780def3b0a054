// The segmenter's sensor model: the noise it adds per point, along a plane's normal, and the
// distance within which planes at range are one.

#include "relplane/segmenter/sensor.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace relplane::segmenter {
namespace {

TEST(SensorOptions, WithoutAPresetTheRangeNoiseStays) {
  const SensorOptions none;
  EXPECT_FALSE(none.Known());
  EXPECT_FALSE(HasPointNoise(none, 0.0f));
  EXPECT_TRUE(HasPointNoise(none, 0.003f));
  // (range_noise r^2)^2 at r = 2
  EXPECT_FLOAT_EQ(PointNoiseVariance(none, 0.003f, 2.0f, 0.0f, 0.0f), 0.012f * 0.012f);
  EXPECT_FLOAT_EQ(none.CoplanarDistance(0.04f, {1, 0, 0}, {5, 0, 0}, {1, 0, 0}, {5, 1, 0}), 0.04f);
}

TEST(SensorOptions, KinectNoiseAtDepthIsTheCamerasResolvedNoise) {
  SensorOptions kinect;
  ASSERT_TRUE(kinect.SetPreset("kinect_v1"));
  EXPECT_FALSE(kinect.SetPreset("kinect"));
  EXPECT_EQ(kinect.preset, "kinect_v1");
  const double z = 4.0;
  const double sigma = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
  const double step = 2.87e-3 * z * z;
  EXPECT_NEAR(PointNoiseVariance(kinect, 0.0f, 4.0f, 1.0f, -0.5f),
              sigma * sigma + step * step / 12.0, 2e-6);
  // Nearer than the camera's minimum: its minimum's.
  EXPECT_FLOAT_EQ(kinect.VarianceAt(0.1f), kinect.VarianceAt(0.5f));
  // Along the normal of a wall square on: all of it; of a floor seen 1 m below at 4 m depth:
  // the ray's share, 1/4.
  const Eigen::Vector3f ahead(4.0f, 0.0f, 0.0f), below(4.0f, 0.0f, -1.0f);
  EXPECT_NEAR(kinect.SigmaAlongNormal({-1, 0, 0}, ahead), std::sqrt(kinect.VarianceAt(4.0f)), 1e-6);
  EXPECT_NEAR(kinect.SigmaAlongNormal({0, 0, 1}, below), 0.25 * std::sqrt(kinect.VarianceAt(4.0f)),
              1e-6);
  // Far walls merge within three times that, near ones within merge_distance.
  EXPECT_NEAR(kinect.CoplanarDistance(0.04f, {-1, 0, 0}, ahead, {-1, 0, 0}, {4, 1, 0}),
              3.0 * std::sqrt(kinect.VarianceAt(4.0f)), 1e-6);
  EXPECT_FLOAT_EQ(kinect.CoplanarDistance(0.04f, {-1, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {1, 1, 0}),
                  0.04f);
}

// A camera returns no depth where its ray meets a surface more than max_incidence_deg (80 for a
// Kinect v1) from the surface's normal, so a plane seen beyond that at its centroid (whose
// incidence is at most its farthest returned point's) is no surface; a margin covers the fit.
TEST(SensorOptions, NoSurfaceIsSeenBeyondTheCamerasIncidenceLimit) {
  SensorOptions kinect;
  ASSERT_TRUE(kinect.SetPreset("kinect_v1"));
  ASSERT_DOUBLE_EQ(kinect.model.max_incidence_deg, 80.0);
  const auto seen_at = [&kinect](double incidence_deg) {
    // A vertical plane 4 m ahead whose normal is incidence_deg from the ray to its centroid.
    const double a = incidence_deg * M_PI / 180.0;
    const Eigen::Vector3f normal(-static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)),
                                 0.0f);
    return kinect.BeyondIncidence(normal, {4.0f, 0.0f, 0.0f});
  };
  EXPECT_FALSE(seen_at(0.0));  // square on
  EXPECT_FALSE(seen_at(79.0));
  EXPECT_FALSE(seen_at(80.0 + kinect.grazing_margin_deg - 0.5));
  EXPECT_TRUE(seen_at(80.0 + kinect.grazing_margin_deg + 0.5));
  EXPECT_TRUE(seen_at(90.0));  // a plane containing its rays
  // Either way the normal faces.
  EXPECT_TRUE(kinect.BeyondIncidence({0.1f, -0.995f, 0.0f}, {4.0f, 0.0f, 0.0f}));
  // Without a camera, or with one that returns at any incidence, nothing is beyond.
  EXPECT_FALSE(SensorOptions{}.BeyondIncidence({0.0f, 1.0f, 0.0f}, {4.0f, 0.0f, 0.0f}));
  SensorOptions any = kinect;
  any.model.max_incidence_deg = 90.0;
  EXPECT_FALSE(any.BeyondIncidence({0.0f, 1.0f, 0.0f}, {4.0f, 0.0f, 0.0f}));
}

}  // namespace
}  // namespace relplane::segmenter
