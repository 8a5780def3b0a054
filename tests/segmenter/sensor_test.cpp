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
  EXPECT_FLOAT_EQ(none.CoplanarDistance(0.04f, {1, 0, 0}, {5, 0, 0}, {1, 0, 0}, {5, 1, 0}),
                  0.04f);
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
  EXPECT_NEAR(kinect.SigmaAlongNormal({-1, 0, 0}, ahead), std::sqrt(kinect.VarianceAt(4.0f)),
              1e-6);
  EXPECT_NEAR(kinect.SigmaAlongNormal({0, 0, 1}, below), 0.25 * std::sqrt(kinect.VarianceAt(4.0f)),
              1e-6);
  // Far walls merge within three times that, near ones within merge_distance.
  EXPECT_NEAR(kinect.CoplanarDistance(0.04f, {-1, 0, 0}, ahead, {-1, 0, 0}, {4, 1, 0}),
              3.0 * std::sqrt(kinect.VarianceAt(4.0f)), 1e-6);
  EXPECT_FLOAT_EQ(kinect.CoplanarDistance(0.04f, {-1, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {1, 1, 0}),
                  0.04f);
}

}  // namespace
}  // namespace relplane::segmenter
