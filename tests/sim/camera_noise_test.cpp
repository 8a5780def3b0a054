// Camera noise models in the simulator: depths on the camera's lattice, noise at range as the
// model's formula gives it, no return where the camera gives none, frames fixed by the seed.

#include "relplane/sim/camera_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "relplane/sim/depth_sensor.hpp"
#include "relplane/sim/world.hpp"

namespace relplane::sim {
namespace {

// One wall square on to a sensor at the origin looking along +x, `distance` ahead, wide and
// tall enough to fill the view.
World WallAhead(double distance) {
  WorldOptions options;
  options.generators.clear();
  options.floor = false;
  options.ceiling = false;
  options.walls.push_back({{distance, 50.0}, {distance, -50.0}, -50.0, 100.0});
  return BuildWorld(options);
}

SensorOptions Camera(const std::string& name) {
  SensorOptions options;
  options.camera = *camera::Preset(name);
  options.max_range = 20.0;
  return options;
}

const geometry::Pose2 kOrigin{0.0, 0.0, 0.0};

// Standard deviation of the depths (x) of a frame of a wall square on: every true depth is the
// wall's distance.
double DepthSigma(const Scan& scan, double* mean_out) {
  const double n = static_cast<double>(scan.points.size());
  double mean = 0.0;
  for (const auto& p : scan.points) mean += p.x() / n;
  double var = 0.0;
  for (const auto& p : scan.points) var += (p.x() - mean) * (p.x() - mean) / (n - 1.0);
  *mean_out = mean;
  return std::sqrt(var);
}

TEST(CameraNoise, KinectDepthsLieOnTheDisparityLattice) {
  const World world = WallAhead(3.3);
  SensorOptions options = Camera("kinect_v1");
  DepthSensor sensor(world, options);
  const Scan scan = sensor.Capture(kOrigin, 4);
  ASSERT_GT(scan.points.size(), 15000u);
  const auto& m = options.camera;
  int levels_seen = 0;
  double last = 0.0;
  for (const auto& p : scan.points) {
    const double disparity_steps = m.focal_px * m.baseline / p.x() / m.disparity_step;
    // float coordinates: a relative error of about 1e-7 of some 200 steps
    ASSERT_NEAR(disparity_steps, std::round(disparity_steps), 1e-3) << p.transpose();
    if (p.x() != last) ++levels_seen;
    last = p.x();
  }
  EXPECT_GT(levels_seen, 100) << "the noise spreads the wall over several lattice values";
}

TEST(CameraNoise, TofDepthsLieOnTheMillimetreLattice) {
  const World world = WallAhead(2.2);
  DepthSensor sensor(world, Camera("tof"));
  const Scan scan = sensor.Capture(kOrigin, 1);
  ASSERT_GT(scan.points.size(), 15000u);
  for (const auto& p : scan.points) {
    ASSERT_NEAR(p.x() * 1000.0, std::round(p.x() * 1000.0), 1e-3);
  }
}

// Without quantization (a disparity step far below the noise) the spread of a square-on wall's
// depths is Nguyen et al.'s sigma_z = 0.0012 + 0.0019 (z - 0.4)^2 at its distance: lateral
// noise moves nothing on a wall square on.
TEST(CameraNoise, KinectAxialNoiseFollowsNguyen) {
  for (double z : {1.0, 3.0, 5.0}) {
    SCOPED_TRACE(z);
    SensorOptions options = Camera("kinect_v1");
    options.camera.disparity_step = 1e-6;
    const World world = WallAhead(z);
    DepthSensor sensor(world, options);
    const Scan scan = sensor.Capture(kOrigin, 2);
    double mean = 0.0;
    const double sigma = DepthSigma(scan, &mean);
    const double expected = 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4);
    const double n = static_cast<double>(scan.points.size());
    EXPECT_NEAR(mean, z, 4.0 * expected / std::sqrt(n));
    // The sample deviation's own standard error is sigma / sqrt(2 n).
    EXPECT_NEAR(sigma, expected, 4.0 * expected / std::sqrt(2.0 * n));
  }
}

// With the 1/8 pixel lattice the spread grows by the quantization's (Sheppard: s^2 / 12), and
// neighbouring reported depths at 5 m are about 2.85e-3 z^2 = 7 cm apart (Khoshelham and
// Elberink 2012).
TEST(CameraNoise, KinectQuantizationAddsItsStep) {
  const double z = 5.0;
  SensorOptions options = Camera("kinect_v1");
  const World world = WallAhead(z);
  DepthSensor sensor(world, options);
  const Scan scan = sensor.Capture(kOrigin, 7);
  double mean = 0.0;
  const double sigma = DepthSigma(scan, &mean);
  const double step = options.camera.DepthStep(z);
  EXPECT_NEAR(step, 2.85e-3 * z * z, 0.02 * step);
  EXPECT_NEAR(sigma, options.camera.ResolvedSigma(z), 0.05 * options.camera.ResolvedSigma(z));
  EXPECT_GT(options.camera.ResolvedSigma(z), options.camera.AxialSigma(z) * 1.05);
}

TEST(CameraNoise, TofNoiseIsSmallerThanKinectAtRange) {
  const World world = WallAhead(4.0);
  double mean = 0.0;
  DepthSensor kinect(world, Camera("kinect_v1"));
  DepthSensor tof(world, Camera("tof"));
  const double kinect_sigma = DepthSigma(kinect.Capture(kOrigin, 3), &mean);
  const double tof_sigma = DepthSigma(tof.Capture(kOrigin, 3), &mean);
  EXPECT_NEAR(tof_sigma, camera::Preset("tof")->ResolvedSigma(4.0), 0.1 * tof_sigma);
  EXPECT_LT(tof_sigma * 4.0, kinect_sigma);
}

TEST(CameraNoise, NoReturnBeyondRangeOrNearerThanTheMinimum) {
  SensorOptions options = Camera("kinect_v1");
  options.camera.lateral_px = 0.0;
  // The wall just past the 6 m limit: the noise brings part of it within, nothing beyond.
  DepthSensor far(WallAhead(6.05), options);
  const Scan scan = far.Capture(kOrigin, 0);
  EXPECT_GT(scan.points.size(), 1000u);
  EXPECT_LT(scan.points.size(), far.Grid().directions.size() * 3 / 4);
  for (const auto& p : scan.points) ASSERT_LE(p.x(), 6.0f + 1e-5f);
  DepthSensor near(WallAhead(0.3), options);
  EXPECT_TRUE(near.Capture(kOrigin, 0).points.empty());
}

TEST(CameraNoise, NoReturnAtGrazingIncidence) {
  const camera::DepthCameraModel model = *camera::Preset("kinect_v1");
  const Eigen::Vector3d ray = Eigen::Vector3d(1.0, 0.2, 0.0).normalized();
  const CameraDraws none;
  // A floor 1 m below: the ray along it meets it at 90 degrees from its normal.
  const Eigen::Vector3d up(0.0, 0.0, 1.0);
  EXPECT_FALSE(MeasurePixel(model, ray, up, 1.0, none).has_value());
  // Tilted 5 degrees down: 85 degrees from the normal, past the 80 degree limit.
  const Eigen::Vector3d down5 = Eigen::Vector3d(1.0, 0.0, -std::tan(5.0 * M_PI / 180.0));
  EXPECT_FALSE(MeasurePixel(model, down5.normalized(), up, 1.0, none).has_value());
  // 20 degrees down: 70 degrees from the normal, returned, on the floor.
  const Eigen::Vector3d down20 = Eigen::Vector3d(1.0, 0.0, -std::tan(20.0 * M_PI / 180.0));
  const auto p = MeasurePixel(model, down20.normalized(), up, 1.0, none);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->z(), -1.0, model.DepthStep(p->x()));
}

TEST(CameraNoise, FramesAreFixedBySeedAndFrame) {
  const World world = WallAhead(2.5);
  SensorOptions options = Camera("kinect_v1");
  options.dropout = 0.1;
  DepthSensor a(world, options), b(world, options);
  a.Capture(kOrigin, 1);
  const Scan a5 = a.Capture(kOrigin, 5), b5 = b.Capture(kOrigin, 5);
  ASSERT_EQ(a5.points.size(), b5.points.size());
  for (size_t i = 0; i < a5.points.size(); ++i) ASSERT_EQ(a5.points[i], b5.points[i]);
  options.seed = 2;
  DepthSensor c(world, options);
  const Scan c5 = c.Capture(kOrigin, 5);
  bool differs = c5.points.size() != a5.points.size();
  for (size_t i = 0; !differs && i < a5.points.size(); ++i) differs = a5.points[i] != c5.points[i];
  EXPECT_TRUE(differs);
}

TEST(CameraNoise, PixelsNameTheirRays) {
  const World world = WallAhead(2.5);
  DepthSensor sensor(world, Camera("kinect_v1"));
  const Scan scan = sensor.Capture(kOrigin, 0);
  ASSERT_EQ(scan.pixels.size(), scan.points.size());
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const Eigen::Vector3d ray = sensor.Grid().directions[static_cast<size_t>(scan.pixels[i])];
    EXPECT_NEAR(scan.points[i].cast<double>().normalized().dot(ray), 1.0, 1e-6);
  }
}

}  // namespace
}  // namespace relplane::sim
