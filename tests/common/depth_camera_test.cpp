// The depth camera models' formulas against their sources' numbers.

#include "relplane/common/depth_camera.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace relplane::camera {
namespace {

TEST(DepthCamera, KinectV1MatchesNguyenAndKhoshelham) {
  const DepthCameraModel m = *Preset("kinect_v1");
  for (double z : {0.5, 1.0, 2.0, 4.0, 6.0}) {
    EXPECT_DOUBLE_EQ(m.AxialSigma(z), 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4));
    // Khoshelham and Elberink 2012: depth resolution about 2.85e-3 z^2.
    EXPECT_NEAR(m.DepthStep(z), 2.85e-3 * z * z, 0.02 * 2.85e-3 * z * z);
  }
}

TEST(DepthCamera, DisparityLatticeStepsGrowWithTheSquareOfDepth) {
  const DepthCameraModel m = *Preset("kinect_v1");
  const double fb = m.focal_px * m.baseline;
  for (double z : {0.7, 2.0, 5.3}) {
    const double q = m.Quantize(z);
    const double steps = fb / q / m.disparity_step;
    EXPECT_NEAR(steps, std::round(steps), 1e-9);
    EXPECT_LE(std::abs(q - z), 0.5 * m.DepthStep(z) * 1.05);
    // Idempotent: a value on the lattice stays.
    EXPECT_DOUBLE_EQ(m.Quantize(q), q);
  }
  EXPECT_EQ(m.Quantize(0.0), 0.0);
  EXPECT_EQ(m.Quantize(-1.0), 0.0);
}

TEST(DepthCamera, DepthLatticeIsMillimetres) {
  const DepthCameraModel m = *Preset("tof");
  EXPECT_DOUBLE_EQ(m.Quantize(1.23449), 1.234);
  EXPECT_DOUBLE_EQ(m.DepthStep(5.0), 0.001);
  EXPECT_NEAR(m.ResolvedSigma(2.0), std::hypot(0.0015 + 0.0012, 0.001 / std::sqrt(12.0)), 1e-12);
}

TEST(DepthCamera, RealSenseFollowsIntelsRmsFormula) {
  const DepthCameraModel m = *Preset("realsense_d435");
  EXPECT_NEAR(m.AxialSigma(2.0), 4.0 * 0.08 / (424.0 * 0.05), 1e-12);
}

TEST(DepthCamera, GaussianIsNoModelAndUnknownNamesAreRefused) {
  const DepthCameraModel none;
  EXPECT_EQ(none.name, "gaussian");
  EXPECT_EQ(none.Quantize(3.21), 3.21);
  EXPECT_EQ(none.ResolvedSigma(3.0), 0.0);
  EXPECT_FALSE(Preset("kinect").has_value());
  EXPECT_EQ(PresetNames().size(), 3u);
}

}  // namespace
}  // namespace relplane::camera
